// The package's types (wasm/index.d.ts, wasm/three.d.ts) compile with tsc --strict against
// a TypeScript file that uses them, and the compiled file, run, finds every declared report
// field among the real values (same keys, same JS types) for planar, surface and remesh runs.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const tsc = join(root, 'node_modules/typescript/bin/tsc');

test('types: tsc --strict compiles tests/types, and the typed fields match real values', { timeout: 300000 }, () => {
  const c = spawnSync(process.execPath, [tsc, '-p', join(root, 'tests/types/tsconfig.json')], { encoding: 'utf8' });
  assert.equal(c.status, 0, `tsc --strict failed:\n${c.stdout}${c.stderr}`);
  const r = spawnSync(process.execPath, [join(root, 'build/types-check/check.js')], { encoding: 'utf8', cwd: root });
  assert.equal(r.status, 0, r.stderr);
  const out = JSON.parse(r.stdout);
  assert.deepEqual(out.problems, []);
  assert.ok(out.planarEdges > 0 && out.surfaceTriangles > 0);
});

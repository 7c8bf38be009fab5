// Repeated runs leave the wasm heap flat: every temporary is freed, in success and error paths.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadAnisomesh } from 'anisomesh';

const am = await loadAnisomesh();
// A small case (about 200 triangles) so that 1,000 cycles stay quick.
const square = {
  domain: {
    outer: [
      { type: 'line', p1: [0, 0], p2: [1, 0] }, { type: 'line', p1: [1, 0], p2: [1, 1] },
      { type: 'line', p1: [1, 1], p2: [0, 1] }, { type: 'line', p1: [0, 1], p2: [0, 0] },
    ],
    holes: [[{ type: 'circle', center: [0.5, 0.5], radius: 0.2 }]],
  },
  controlSpace: { kind: 'quadtree', hmax: 0.1, gradation: 2 },
  sources: [{ type: 'radial', center: [0.2, 0.2], metric: { alpha: 0.5, h1: 0.03, h2: 0.08 }, radius: 0.1 }],
};

test('1,000 mesh-and-dispose cycles leave the heap flat', { timeout: 300000 }, () => {
  const cycle = (i) => {
    const { mesh } = am.meshCase(square);
    am.meshCase(square, { stats: false, measures: true }).report();  // the run kept for its report, freed by it
    am.meshCase(square, { stats: false }).dispose();                 // or freed unreported
    const cs = am.createControlSpace(square);
    cs.metricsAt(new Float64Array([0.5, 0.5]));
    const other = am.createControlSpace(square);
    const both = am.minimumControlSpace(cs, other);  // shares its inputs: freed with the last owner
    cs.dispose();
    other.dispose();
    both.metricsAt(new Float64Array([0.5, 0.5]));
    both.dispose();
    am.writeMesh(mesh, i % 2 ? 'vtk' : 'mesh');
    try { am.meshCase({ domain: 'bad' }); } catch { /* error paths must free too */ }
    try { am.metric({ h1: -1, h2: 1 }); } catch { /* ditto */ }
  };
  for (let i = 0; i < 20; i++) cycle(i);  // warm up: first-use allocations
  const before = am.memoryStats();
  for (let i = 0; i < 1000; i++) cycle(i);
  const after = am.memoryStats();
  console.log(`heap in use: ${before.inUseBytes} -> ${after.inUseBytes} bytes; heap size ${before.heapBytes} -> ${after.heapBytes}`);
  // A leak of even 16 bytes per cycle would add 16 kB.
  assert.ok(after.inUseBytes - before.inUseBytes < 16 * 1024, `in use grew by ${after.inUseBytes - before.inUseBytes} bytes`);
  assert.equal(after.heapBytes, before.heapBytes);
});

// A callback that throws: the exception must not unwind through the core's frames (their
// destructors would not run: 136-536 bytes per call leaked in the single-threaded module,
// 17-66 kB in the threaded one). The JS layer catches it, cancels the run and throws it
// once the core has returned.
test('a throwing onProgress / onStage cancels the run, throws its own error and leaks nothing', { timeout: 300000 }, () => {
  const boom = new Error('boom');
  const { mesh } = am.meshCase(square);
  const calls = [
    () => am.meshCase(square, { onProgress: (x) => { if (x > 0.3) throw boom; } }),
    () => am.meshCase(square, { onProgress: () => { throw boom; } }),
    () => am.remesh(mesh, null, { hsiz: 0.05, onProgress: (x) => { if (x > 0.3) throw boom; } }),
    () => am.remesh(mesh, null, { hsiz: 0.05, onStage: (s) => { if (s === 'meshing') throw boom; } }),
    () => am.remesh(mesh, null, { hsiz: 0.05, onStage: (s) => { if (s === 'output') throw boom; } }),
  ];
  for (const call of calls) assert.throws(call, (e) => e === boom);
  // Returning false from onStage cancels as onProgress does.
  assert.throws(() => am.remesh(mesh, null, { hsiz: 0.05, onStage: () => false }), (e) => e.code === 'CANCELLED');
  for (let i = 0; i < 10; i++) for (const call of calls) try { call(); } catch { /* warm up */ }
  const before = am.memoryStats();
  for (let i = 0; i < 100; i++) for (const call of calls) try { call(); } catch { /* counted below */ }
  const after = am.memoryStats();
  console.log(`heap in use: ${before.inUseBytes} -> ${after.inUseBytes} bytes over 500 throwing callbacks`);
  assert.ok(after.inUseBytes - before.inUseBytes < 8 * 1024, `in use grew by ${after.inUseBytes - before.inUseBytes} bytes`);
  assert.equal(am.meshCase(square).mesh.triangles.length, mesh.triangles.length, 'the module is still usable');
});

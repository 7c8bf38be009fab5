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

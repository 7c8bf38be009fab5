// Adaptation through the package: adapt() with expressions and with values, metricFromField(),
// typed errors for bad input.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const am = await loadAnisomesh();
const square = am.readMesh(readFileSync(new URL('../../examples/adaptation/square.mesh', import.meta.url), 'utf8'));
const n = square.vertices.length / 2;
const layer = (x, y) => Math.tanh(30 * (x + y - 1));
const values = new Float64Array(n).map((_, i) => layer(square.vertices[2 * i], square.vertices[2 * i + 1]));

test('adapt() to an expression: N vertices, errors reported, refined along the layer', () => {
  const r = am.adapt(square, 'tanh(30*(x+y-1))', { nv: 1500, norm: 2, hmax: 0.2, iterations: 3 });
  assert.equal(r.iterations.length, 3);
  const last = r.iterations[2];
  const m = r.mesh.vertices.length / 2;
  assert.equal(last.vertices, m);
  assert.ok(Math.abs(m - 1500) < 150, `${m} vertices`);
  assert.ok(last.errorLinf > 0 && last.errorL2 > 0 && last.errorLinf < r.iterations[0].errorLinf * 2);
  assert.equal(r.fields[0].length, m);
  // Most vertices near the layer x + y = 1 (|x + y - 1| < 0.1 is 14% of the square).
  let near = 0;
  for (let i = 0; i < m; ++i) if (Math.abs(r.mesh.vertices[2 * i] + r.mesh.vertices[2 * i + 1] - 1) < 0.1) ++near;
  assert.ok(near > 0.5 * m, `${near} of ${m} vertices near the layer`);
});

test('adapt() to values transfers them; metricFromField() gives m11, m12, m22 per vertex', () => {
  const r = am.adapt(square, [values], { err: 0.01, iterations: 1 });
  const m = r.mesh.vertices.length / 2;
  assert.equal(r.fields.length, 1);
  assert.equal(r.fields[0].length, m);
  assert.equal(r.iterations[0].errorLinf, undefined);
  const f = am.metricFromField(square, values, { nv: 2000 });
  assert.equal(f.metrics.length, 3 * n);
  assert.ok(Math.abs(f.expectedVertices - 2000) < 1e-6 * 2000);
  for (let i = 0; i < n; ++i) assert.ok(f.metrics[3 * i] > 0 && f.metrics[3 * i] * f.metrics[3 * i + 2] > f.metrics[3 * i + 1] ** 2);
});

test('adapt() with measures: the last mesh measured in the adaptation metric (edges, lengths, qualities)', () => {
  const r = am.adapt(square, 'tanh(30*(x+y-1))', { nv: 800, norm: 2, hmax: 0.2, iterations: 2, measures: true });
  const nt = r.mesh.triangles.length / 3, nv = r.mesh.vertices.length / 2;
  const { edges, edgeLength, quality, vertexH } = r.measures;
  assert.equal(quality.length, nt);
  assert.equal(vertexH.length, nv);
  assert.equal(edgeLength.length, edges.length / 2);
  assert.equal(edges.length / 2, nv + nt - 1, 'Euler: E = V + F - 1 on a disc');
  const within = edgeLength.filter((l) => l > Math.SQRT1_2 && l < Math.SQRT2).length / edgeLength.length;
  assert.ok(within > 0.8, `${within} of the edges within [1/sqrt2, sqrt2] of the adaptation metric`);
  assert.equal(am.adapt(square, 'x*x', { nv: 200, iterations: 1 }).measures, undefined);
});

test('bad input gives coded errors', () => {
  const code = (f) => {
    try {
      f();
    } catch (e) {
      assert.ok(e instanceof AnisomeshError);
      return e.code;
    }
    return 'none';
  };
  assert.equal(code(() => am.adapt(square, [new Float64Array(3)], { nv: 100 })), 'INVALID_ARGUMENT');
  const bad = values.slice();
  bad[5] = NaN;
  assert.equal(code(() => am.adapt(square, [bad], { nv: 100 })), 'INVALID_ARGUMENT');
  assert.equal(code(() => am.adapt(square, 'x^2', { nv: 1e9 })), 'ELEMENT_BUDGET_EXCEEDED');
  assert.equal(code(() => am.adapt(square, 'x^', { nv: 100 })), 'PARSE_ERROR');
  assert.equal(code(() => am.adapt(square, 'x^2', { nv: 100, err: 0.1 })), 'INVALID_ARGUMENT');
  assert.equal(code(() => am.adapt(square, 'x^2', { nv: 100, norm: 3 })), 'INVALID_ARGUMENT');
  // The CLI's -iterations range: the package has no callback to stop a loop of 1e9 runs.
  for (const iterations of [0, 1001, 1e9, 2 ** 40]) {
    assert.equal(code(() => am.adapt(square, 'x^2', { nv: 100, iterations })), 'INVALID_ARGUMENT', `iterations ${iterations}`);
  }
  assert.equal(code(() => am.metricFromField(square, [], { nv: 100 })), 'INVALID_ARGUMENT');
  // A constant field: hmax everywhere (a documented result, not an error).
  const c = am.metricFromField(square, new Float64Array(n).fill(2), { nv: 100, hmax: 0.25 });
  for (let i = 0; i < n; ++i) assert.ok(Math.abs(c.metrics[3 * i] - 16) < 1e-9 && Math.abs(c.metrics[3 * i + 1]) < 1e-9);
});

// Meshing, I/O and control spaces through the package, as a user would call them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const am = await loadAnisomesh();
const example = (name) => JSON.parse(readFileSync(new URL(`../../examples/${name}.json`, import.meta.url), 'utf8'));

test('meshCase returns typed arrays that describe a valid planar mesh', () => {
  const { mesh, stats } = am.meshCase(example('point_source'));
  assert.equal(mesh.dimension, 2);
  assert.ok(mesh.vertices instanceof Float64Array && mesh.triangles instanceof Uint32Array);
  assert.ok(mesh.positions instanceof Float32Array && mesh.positions.length === 3 * (mesh.vertices.length / 2));
  const n = mesh.vertices.length / 2;
  assert.equal(stats.vertices, n);
  assert.equal(stats.triangles, mesh.triangles.length / 3);
  assert.equal(stats.inverted, 0);
  for (const i of mesh.triangles) assert.ok(i < n);
  // Counter-clockwise triangles with positive area.
  const v = mesh.vertices;
  for (let t = 0; t < mesh.triangles.length; t += 3) {
    const [a, b, c] = [mesh.triangles[t], mesh.triangles[t + 1], mesh.triangles[t + 2]];
    const area = (v[2 * b] - v[2 * a]) * (v[2 * c + 1] - v[2 * a + 1]) - (v[2 * c] - v[2 * a]) * (v[2 * b + 1] - v[2 * a + 1]);
    assert.ok(area > 0, `triangle ${t / 3} has area ${area}`);
  }
  assert.ok(mesh.edges.length > 0 && mesh.edgeRefs.length === mesh.edges.length / 2);
});

test('meshCase with stats: false and measures: the mesh at once, the same report from result.report() after', () => {
  for (const [name, options] of [['fig7_rect_holes_dr2', {}], ['boundary_layer', { quads: true }]]) {
    const c = example(name);
    const full = am.meshCase(c, options);
    const quick = am.meshCase(c, { ...options, stats: false, measures: true });
    assert.equal(quick.stats, null, name);
    assert.deepEqual(quick.mesh.triangles, full.mesh.triangles, name);
    assert.deepEqual(quick.mesh.quads, full.mesh.quads, name);
    // Per-edge lengths and per-element qualities measured as the report measures them.
    const { edges, edgeLength, quality, vertexH } = quick.measures;
    const s = full.stats;
    assert.equal(edges.length / 2, s.edges, name);
    assert.equal(edgeLength.length, s.edges, name);
    assert.equal(quality.length, s.triangles + s.quads, name);
    assert.equal(vertexH.length, s.vertices, name);
    if (options.quads) assert.ok(s.quads > 0, `${name}: quads`);
    const mean = (a) => a.reduce((x, y) => x + y, 0) / a.length;
    assert.ok(Math.abs(mean(quality) - s.quality.mean) < 1e-6, `${name}: mean Q ${mean(quality)} vs ${s.quality.mean}`);
    assert.ok(Math.abs(mean(edgeLength) - s.edgeLength.mean) < 1e-6, `${name}: mean length ${mean(edgeLength)} vs ${s.edgeLength.mean}`);
    const within = edgeLength.filter((l) => l >= Math.SQRT1_2 && l <= Math.SQRT2).length / edgeLength.length;
    assert.ok(Math.abs(within - s.edgeLength.fractionWithinSqrt2) < 1e-4, `${name}: ${within} vs ${s.edgeLength.fractionWithinSqrt2}`);
    assert.ok(vertexH.every((h) => h > 0 && h <= c.controlSpace.hmax * 1.0001), `${name}: sizes within (0, hmax]`);
    // Sorted distinct pairs a < b.
    for (let e = 0; e < edges.length; e += 2) {
      assert.ok(edges[e] < edges[e + 1], name);
      if (e) assert.ok(edges[e - 2] < edges[e] || (edges[e - 2] === edges[e] && edges[e - 1] < edges[e + 1]), name);
    }
    const later = quick.report();
    const strip = ({ pipelineSeconds, timings, ...rest }) => rest;  // times differ between runs
    assert.deepEqual(strip(later), strip(full.stats), name);
    assert.deepEqual(Object.keys(later.pipelineSeconds), Object.keys(full.stats.pipelineSeconds), name);
    assert.ok(quick.timings.runMs > 0 && quick.timings.measuresMs >= 0, name);
    // The kept run is used up by its report.
    assert.throws(() => quick.report(), { code: 'INVALID_ARGUMENT', message: /already made/ });
  }
  // Each run keeps its own: two runs with stats: false report in any order (no "last run").
  const a = am.meshCase(example('fig7_rect_holes_dr2'), { stats: false });
  const b = am.meshCase(example('point_source'), { stats: false });
  assert.equal(b.report().triangles, b.mesh.triangles.length / 3);
  assert.equal(a.report().triangles, a.mesh.triangles.length / 3);
  const d = am.meshCase(example('point_source'), { stats: false });
  d.dispose();
  assert.throws(() => d.report(), { code: 'INVALID_ARGUMENT', message: /disposed/ });
  assert.equal(am.meshCase(example('point_source')).report, undefined, 'a run with its stats keeps nothing');
  assert.throws(() => am.meshCase(example('point_source'), { stats: 'no' }), { code: 'INVALID_ARGUMENT', message: /options\.stats/ });
  assert.throws(() => am.meshCase(example('point_source'), { measures: 1 }), { code: 'INVALID_ARGUMENT', message: /options\.measures/ });
});

test('the same case gives the same mesh twice (deterministic)', () => {
  const a = am.meshCase(example('fig6_rect_holes_nosmooth')).mesh;
  const b = am.meshCase(example('fig6_rect_holes_nosmooth')).mesh;
  assert.deepEqual(a.vertices, b.vertices);
  assert.deepEqual(a.triangles, b.triangles);
});

test('Medit, VTK and OBJ round trips keep counts', () => {
  const { mesh } = am.meshCase(example('point_source'));
  for (const format of ['mesh', 'vtk', 'obj']) {
    const back = am.readMesh(am.writeMesh(mesh, format), format);
    assert.equal(back.vertices.length / back.dimension, mesh.vertices.length / 2, format);
    assert.equal(back.triangles.length, mesh.triangles.length, format);
  }
  assert.match(am.writeMesh(mesh, 'svg'), /^<svg/);
});

test('text formats and .sol also read from their UTF-8 bytes (a file read without decoding)', () => {
  const { mesh } = am.meshCase(example('point_source'));
  const n = mesh.vertices.length / 2;
  const utf8 = (s) => new TextEncoder().encode(s);
  for (const format of ['mesh', 'vtk', 'obj', 'msh']) {
    const text = am.writeMesh(mesh, format);
    const fromBytes = am.readMesh(utf8(text), format), fromText = am.readMesh(text, format);
    assert.deepEqual(fromBytes.vertices, fromText.vertices, format);
    assert.deepEqual(fromBytes.triangles, fromText.triangles, format);
  }
  const metrics = new Float64Array(3 * n).map((_, i) => (i % 3 === 1 ? 0 : 400 + i));
  const sol = am.writeSol(metrics);
  assert.deepEqual(am.readSol(Buffer.from(sol), n), am.readSol(sol, n));  // a Node Buffer is a Uint8Array
  assert.throws(() => am.readSol(utf8(sol), n + 1), { code: 'PARSE_ERROR' });
  assert.throws(() => am.readMesh(12), { code: 'INVALID_ARGUMENT', message: /string or its UTF-8 bytes/ });
  assert.throws(() => am.readSol([1, 2], n), { code: 'INVALID_ARGUMENT', message: /string or its UTF-8 bytes/ });
});

test('binary Medit .meshb: bytes as the native writer writes them, read back identical', () => {
  const { mesh } = am.meshCase(example('point_source'));
  const bytes = am.writeMesh(mesh, 'meshb');
  assert.ok(bytes instanceof Uint8Array);
  assert.deepEqual([...bytes.subarray(0, 8)], [1, 0, 0, 0, 2, 0, 0, 0]);  // code 1, version 2
  const back = am.readMesh(bytes, 'meshb');
  assert.deepEqual(back.vertices, mesh.vertices);
  assert.deepEqual(back.triangles, mesh.triangles);
  assert.deepEqual(back.edgeRefs, mesh.edgeRefs);
  assert.equal(am.writeMesh(back, 'mesh'), am.writeMesh(mesh, 'mesh'));
  assert.throws(() => am.readMesh(bytes.subarray(0, bytes.length - 9), 'meshb'), (e) => e.code === 'PARSE_ERROR' && /Medit binary mesh, byte \d+/.test(e.message));
  assert.throws(() => am.readMesh('text', 'meshb'), (e) => e.code === 'INVALID_ARGUMENT');
});

test('.sol tensors round trip and drive remesh', () => {
  const { mesh } = am.meshCase(example('point_source'));
  const n = mesh.vertices.length / 2;
  const metrics = new Float64Array(3 * n);
  for (let i = 0; i < n; i++) metrics.set([400, 0, 400], 3 * i);  // isotropic h = 0.05
  const back = am.readSol(am.writeSol(metrics), n);
  assert.deepEqual(Array.from(back.slice(0, 3)), [400, 0, 400]);
  const r = am.remesh(mesh, back);
  assert.ok(r.mesh.triangles.length > 0);
  assert.throws(() => am.readSol(am.writeSol(metrics), n + 1), AnisomeshError);
  assert.throws(() => am.remesh(mesh, back, { hmin: '0.1' }), { code: 'INVALID_ARGUMENT', message: /options\.hmin/ });
  assert.throws(() => am.remesh(mesh, back, { hgrad: NaN }), { code: 'INVALID_ARGUMENT', message: /options\.hgrad/ });
  assert.throws(() => am.remesh(mesh, back, { maxElements: 1.5 }), { code: 'INVALID_ARGUMENT', message: /options\.maxElements/ });
  // hgrad in (0, 1) reaches the core's own check.
  assert.throws(() => am.remesh(mesh, back, { hgrad: 0.5 }), { code: 'INVALID_ARGUMENT' });
});

test('remesh with stats: false: the same mesh, no report until report(); onStage marks the stages', () => {
  const { mesh } = am.meshCase(example('point_source'));
  const n = mesh.vertices.length / 2;
  const metrics = new Float64Array(3 * n);
  for (let i = 0; i < n; i++) metrics.set([400 + i % 7, 3, 300], 3 * i);
  const full = am.remesh(mesh, metrics);
  const stages = [];
  const quick = am.remesh(mesh, metrics, { stats: false, onStage: (name) => stages.push(name) });
  assert.equal(quick.stats, null);
  assert.deepEqual(stages, ['boundary', 'control space', 'discretization', 'meshing', 'output']);
  assert.deepEqual(quick.mesh.triangles, full.mesh.triangles);
  assert.deepEqual(quick.mesh.vertices, full.mesh.vertices);
  const strip = ({ pipelineSeconds, timings, ...rest }) => rest;  // times differ between runs
  assert.deepEqual(strip(quick.report()), strip(full.stats));
  assert.throws(() => quick.report(), { code: 'INVALID_ARGUMENT', message: /already made/ });
  assert.equal(full.report, undefined, 'a run with its stats keeps nothing');
  const d = am.remesh(mesh, metrics, { stats: false });
  d.dispose();
  assert.throws(() => d.report(), { code: 'INVALID_ARGUMENT', message: /disposed/ });
  assert.throws(() => am.remesh(mesh, metrics, { stats: 0 }), { code: 'INVALID_ARGUMENT', message: /options\.stats/ });
  assert.throws(() => am.remesh(mesh, metrics, { onStage: 'x' }), { code: 'INVALID_ARGUMENT', message: /options\.onStage/ });
});

test('large texts out of the core (decoded in one pass) are the texts written', () => {
  const { mesh } = am.meshCase(example('fig7_rect_holes_dr2'));
  const text = am.writeMesh(mesh, 'mesh');
  assert.ok(text.length > 1 << 12, `${text.length} characters: past the one-pass decoding threshold`);
  // Read back and written again: the same text (and the same mesh), for every text format.
  assert.equal(am.writeMesh(am.readMesh(text), 'mesh'), text);
  assert.equal(am.writeMesh(am.readMesh(new TextEncoder().encode(text)), 'mesh'), text);
  assert.ok(text.startsWith('MeshVersionFormatted') && text.trimEnd().endsWith('End'));
  for (const format of ['vtk', 'obj', 'msh', 'msh2']) {
    const t = am.writeMesh(mesh, format);
    assert.equal(am.writeMesh(am.readMesh(t, format), format), t, format);
  }
});

test('control space: queries, inspection, dispose', () => {
  const cs = am.createControlSpace(example('point_source'));
  const m = cs.metricAt([0.5, 0.5]);
  assert.ok(m.m11 > 0 && m.m22 > 0);
  const many = cs.metricsAt(new Float64Array([0.1, 0.1, 0.9, 0.9]));
  assert.equal(many.length, 6);
  const info = cs.inspect();
  assert.ok(info && typeof info === 'object');
  cs.dispose();
  cs.dispose();  // twice is fine
  assert.throws(() => cs.metricAt([0, 0]), { code: 'INVALID_ARGUMENT', message: /after dispose/ });
});

test('minimumControlSpace: the exact intersection of the inputs at random points, valid after they are disposed', () => {
  const a = am.createControlSpace(example('point_source'));
  const b = am.createControlSpace(example('boundary_layer'));
  const c = am.createControlSpace(example('expression_field'));
  const min = am.minimumControlSpace(a, b, c);
  // Deterministic pseudo-random points in the unit square (inside every input's box).
  let seed = 7;
  const rand = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  const xy = new Float64Array(2 * 2000).map(() => 0.02 + 0.96 * rand());
  const [ma, mb, mc, mm] = [a, b, c, min].map((cs) => cs.metricsAt(xy));
  // Size along direction d: 1 / sqrt(d^T M d). The minimum's is <= every input's.
  const size = (m, i, t) => 1 / Math.sqrt(m[3 * i] * Math.cos(t) ** 2 + 2 * m[3 * i + 1] * Math.cos(t) * Math.sin(t) + m[3 * i + 2] * Math.sin(t) ** 2);
  let equalToAnInput = 0;
  for (let i = 0; i < xy.length / 2; i++) {
    for (let k = 0; k < 16; k++) {
      const t = (k * Math.PI) / 16;
      for (const m of [ma, mb, mc]) assert.ok(size(mm, i, t) <= size(m, i, t) * (1 + 1e-9), `point ${i}, angle ${t}`);
    }
    // And it is the core's minimum of all three at once (intersection is not associative):
    // an input inside both others where there is one, else the intersection folded pairwise.
    const pick = (m) => ({ m11: m[3 * i], m12: m[3 * i + 1], m22: m[3 * i + 2] });
    const exact = am.intersectMetrics(am.intersectMetrics(pick(ma), pick(mb)), pick(mc));
    const isInput = (m) => m[3 * i] === mm[3 * i] && m[3 * i + 1] === mm[3 * i + 1] && m[3 * i + 2] === mm[3 * i + 2];
    const insideOthers = (m) => [ma, mb, mc].every((o) => Array.from({ length: 16 }, (_, k) => (k * Math.PI) / 16)
      .every((t) => size(m, i, t) <= size(o, i, t) * (1 + 1e-9)));
    const folded = Math.abs(exact.m11 - mm[3 * i]) <= 1e-9 * exact.m11 && Math.abs(exact.m22 - mm[3 * i + 2]) <= 1e-9 * exact.m22;
    assert.ok(folded || [ma, mb, mc].some((m) => isInput(m) && insideOthers(m)), `point ${i}`);
    if ([ma, mb, mc].some((m) => m[3 * i] === mm[3 * i] && m[3 * i + 1] === mm[3 * i + 1] && m[3 * i + 2] === mm[3 * i + 2])) equalToAnInput++;
  }
  assert.ok(equalToAnInput > 0, 'where one input is the smallest, the minimum is that input');
  a.dispose(); b.dispose(); c.dispose();
  assert.deepEqual(min.metricsAt(xy.subarray(0, 20)), mm.subarray(0, 30));
  assert.equal(min.inspect({ sampleGrid: 8 }).samples.length, 64);  // no structure: sampled on a grid
  assert.throws(() => min.toVtk(), { code: 'INVALID_ARGUMENT', message: /adaptive/ });
  min.dispose();
  assert.throws(() => am.minimumControlSpace(min), { code: 'INVALID_ARGUMENT' });
  assert.throws(() => am.minimumControlSpace({}, {}), { code: 'INVALID_ARGUMENT', message: /ControlSpace/ });
});

test('bad input becomes AnisomeshError naming the problem; the module keeps working', () => {
  const check = (fn, code, message) => assert.throws(fn, (e) => {
    assert.ok(e instanceof AnisomeshError, String(e));
    assert.equal(e.code, code, e.message);
    assert.match(e.message, message);
    return true;
  });
  check(() => am.meshCase('{"domain": '), 'PARSE_ERROR', /./);
  check(() => am.meshCase({ domain: 3 }), 'PARSE_ERROR', /domain/);
  const open = example('point_source');
  check(() => am.evaluateExpression('sin(u'), 'PARSE_ERROR', /column/);
  check(() => am.writeMesh({ dimension: 2, vertices: new Float32Array(4) }), 'INVALID_ARGUMENT', /mesh\.vertices: expected a Float64Array/);
  check(() => am.writeMesh({ dimension: 2, vertices: new Float64Array(3) }), 'INVALID_ARGUMENT', /multiple of dimension/);
  check(() => am.writeMesh({ dimension: 2, vertices: new Float64Array(4), triangles: new Uint32Array([0, 1, 5]) }), 'INVALID_ARGUMENT', /out of range/);
  check(() => am.writeMesh({ dimension: 2, vertices: new Float64Array(4) }, 'stl'), 'INVALID_ARGUMENT', /unknown mesh format/);
  check(() => am.readMesh('MeshVersionFormatted 1\nDimension 2\nVertices\n2\n0 0\n', 'mesh'), 'PARSE_ERROR', /line/);
  check(() => am.createControlSpace('not json'), 'PARSE_ERROR', /./);
  // Still works.
  assert.ok(am.meshCase(open).mesh.triangles.length > 0);
});

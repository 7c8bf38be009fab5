// Surface cases and SVG domains through the package: per-patch control spaces
// (createControlSpace(surfaceCase, { patch })), the overlay glyphs, per-corner patch
// parameters and 3D qualities from meshCase, and domainFromSvg.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const am = await loadAnisomesh();
const surface = (name) => readFileSync(new URL(`../../examples/surface/${name}.json`, import.meta.url), 'utf8');

test('createControlSpace of a surface case: each patch its own (u, v) control space', () => {
  const text = surface('surface_two_patch_c');
  const a = am.createControlSpace(text, { patch: 0 }), b = am.createControlSpace(JSON.parse(text), { patch: 1 });
  try {
    // Patch A carries the fine C-shaped source; B far from the shared edge is coarse.
    const [ma, mb] = [a.metricAt([0.2, 0.5]), b.metricAt([0.8, 0.5])];
    assert.ok(ma.m11 > 0 && mb.m11 > 0);
    assert.ok(a.inspect().nodes.length > 0);
    assert.match(a.toVtk(), /^# vtk DataFile[\s\S]*TENSORS metric/);
    assert.notDeepEqual(a.inspect().nodes.length, b.inspect().nodes.length);
  } finally {
    a.dispose();
    b.dispose();
  }
  assert.throws(() => am.createControlSpace(text, { patch: 2 }), (e) => e instanceof AnisomeshError && e.code === 'INVALID_ARGUMENT' && /2 patches/.test(e.message));
  assert.throws(() => am.createControlSpace(text, { patch: -1 }), (e) => e.code === 'INVALID_ARGUMENT');
});

test('meshCase of a surface: glyphs, element patches, corner parameters and 3D qualities', () => {
  const r = am.meshCase(surface('surface_two_patch_c'), { measures: true, controlSpaceGlyphs: true, patchParams: true });
  const nt = r.mesh.triangles.length / 3, nq = r.mesh.quads.length / 4;
  assert.equal(r.elementPatch.length, nt + nq);
  assert.equal(r.cornerParams.length, 2 * (3 * nt + 4 * nq));
  assert.deepEqual([...new Set(r.elementPatch)].sort(), [0, 1]);
  assert.equal(r.measures.quality.length, nt + nq);
  const mean = r.measures.quality.reduce((s, x) => s + x, 0) / (nt + nq);
  assert.ok(Math.abs(mean - r.stats.quality.mean) < 1e-4, `${mean} vs ${r.stats.quality.mean}`);
  assert.equal(r.measures.edgeLength.length, r.measures.edges.length / 2);
  const lmean = r.measures.edgeLength.reduce((s, x) => s + x, 0) / r.measures.edgeLength.length;
  assert.ok(Math.abs(lmean - r.stats.edgeLength.mean) < 1e-4, `${lmean} vs ${r.stats.edgeLength.mean}`);
  const g = r.glyphs;
  assert.ok(g.patch.length > 10 && g.offsets.length === g.patch.length + 1);
  assert.equal(g.uv.length / 2, g.offsets.at(-1));
  assert.equal(g.xyz.length / 3, g.offsets.at(-1));
  // Without the options: none of it.
  const plain = am.meshCase(surface('surface_two_patch_c'));
  assert.equal(plain.glyphs, undefined);
  assert.equal(plain.cornerParams, undefined);
});

test('meshCase of a surface with stats: false: the mesh and its measures first, the same report from report() after', () => {
  const strip = ({ secondsTotal, curvatureSeconds, controlSpaceSeconds, ...rest }) => rest;  // times differ
  for (const [name, options] of [['surface_p2_holes', {}], ['surface_two_patch_c', { quads: true }]]) {
    const full = am.meshCase(surface(name), { ...options, measures: true });
    const quick = am.meshCase(surface(name), { ...options, stats: false, measures: true });
    assert.equal(quick.stats, null, name);
    assert.deepEqual(quick.mesh.triangles, full.mesh.triangles, name);
    assert.deepEqual(quick.mesh.quads, full.mesh.quads, name);
    // The per-element 3D values come with the mesh (the page colours by them).
    assert.deepEqual(quick.measures.quality, full.measures.quality, name);
    assert.deepEqual(quick.measures.edgeLength, full.measures.edgeLength, name);
    const later = quick.report();
    assert.deepEqual(strip(later), strip(full.stats), name);
    assert.ok(later.quality3d.chordDeviationMax > 0, name);
    assert.throws(() => quick.report(), { code: 'INVALID_ARGUMENT', message: /already made/ });
  }
  // elementMeasures: false: the colours later from elementMeasures() (the page's drags), the same values.
  const full = am.meshCase(surface('surface_p2_holes'), { measures: true });
  const bare = am.meshCase(surface('surface_p2_holes'), { stats: false, measures: true, elementMeasures: false });
  assert.equal(bare.measures.quality, undefined);
  assert.equal(bare.measures.edgeLength, undefined);
  assert.deepEqual(bare.measures.edges, full.measures.edges);
  const em = bare.elementMeasures();
  assert.deepEqual(em.quality, full.measures.quality);
  assert.deepEqual(em.edgeLength, full.measures.edgeLength);
  assert.deepEqual(strip(bare.report()), strip(full.stats));
  assert.throws(() => bare.elementMeasures(), { code: 'INVALID_ARGUMENT', message: /already made/ });
  const planar = am.meshCase({ domain: { outer: [{ type: 'polyline', points: [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]] }] }, controlSpace: { hmax: 0.2 } }, { stats: false });
  assert.throws(() => planar.elementMeasures(), { code: 'INVALID_ARGUMENT', message: /not a surface run/ });
  planar.dispose();
  assert.throws(() => am.meshCase(surface('surface_torus'), { elementMeasures: 0 }), { code: 'INVALID_ARGUMENT', message: /options\.elementMeasures/ });
  const d = am.meshCase(surface('surface_torus'), { stats: false });
  d.dispose();
  assert.throws(() => d.report(), { code: 'INVALID_ARGUMENT', message: /disposed/ });
});

test('domainFromSvg: a drawing with a hole is a domain that meshes', () => {
  const d = am.domainFromSvg('<svg><path d="M0 0 h100 v50 h-100 z"/><circle cx="50" cy="25" r="10"/></svg>', { size: 4 });
  assert.equal(d.holes.length, 1);
  const { mesh, stats } = am.meshCase({ domain: d, controlSpace: { hmin: 0.1, hmax: 0.1 } });
  let area = 0;
  const v = mesh.vertices;
  for (let t = 0; t < mesh.triangles.length; t += 3) {
    const [a, b, c] = [mesh.triangles[t], mesh.triangles[t + 1], mesh.triangles[t + 2]];
    area += 0.5 * ((v[2 * b] - v[2 * a]) * (v[2 * c + 1] - v[2 * a + 1]) - (v[2 * c] - v[2 * a]) * (v[2 * b + 1] - v[2 * a + 1]));
  }
  assert.ok(Math.abs(area - (8 - Math.PI * 0.16)) < 0.01, `area ${area}`);
  assert.equal(stats.inverted, 0);
  assert.throws(() => am.domainFromSvg('<svg><path d="M0 0 L1 0 L1 1"/></svg>'), (e) => e.code === 'OPEN_CONTOUR');
  assert.throws(() => am.domainFromSvg('<svg/>'), (e) => e.code === 'INVALID_DOMAIN');
  assert.throws(() => am.domainFromSvg(42), (e) => e.code === 'INVALID_ARGUMENT');
  assert.throws(() => am.domainFromSvg('<svg/>', { size: 0 }), (e) => e.code === 'INVALID_ARGUMENT');
});

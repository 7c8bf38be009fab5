// 'anisomesh/three': display objects built from package results, as a three.js user would.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadAnisomesh } from 'anisomesh';
import { meshGeometry, meshEdges, controlSpaceCells, metricEllipses } from 'anisomesh/three';

const am = await loadAnisomesh();
const c = JSON.parse(readFileSync(new URL('../../examples/point_source.json', import.meta.url), 'utf8'));

test('mesh geometry and edges', () => {
  const { mesh, stats } = am.meshCase(c, { quads: true });
  const g = meshGeometry(mesh);
  assert.equal(g.getAttribute('position').count, stats.vertices);
  assert.ok(g.getAttribute('position').array instanceof Float32Array);
  assert.equal(g.getIndex().count, 3 * stats.triangles + 6 * stats.quads);
  const edges = meshEdges(mesh);
  assert.equal(edges.geometry.getIndex().count, 2 * stats.edges);
});

test('control space cells and metric ellipses', () => {
  const cs = am.createControlSpace(c);
  const info = cs.inspect();
  cs.dispose();
  const cells = controlSpaceCells(info);
  const sides = info.cells.reduce((s, cell) => s + cell.length, 0);
  assert.equal(cells.geometry.getAttribute('position').count, 2 * sides);
  const ellipses = metricEllipses(info, { segments: 8 });
  assert.equal(ellipses.geometry.getAttribute('position').count, info.nodes.length * 16);
});

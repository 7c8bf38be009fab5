// The page's edges drawn by the faces (web/wireframe.js): each triangle side's code is its
// mesh edge's, a quad's diagonal is no edge, for the core's sorted edge list or any other order.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fillEdgeCodes, NO_EDGE } from '../../web/wireframe.js';
import { uniqueEdges } from '../../web/measure.js';

// Two triangles and a quad (drawn as (2 3 5), (2 5 4)).
const mesh = { triangles: Uint32Array.from([0, 1, 2, 2, 1, 3]), quads: Uint32Array.from([2, 3, 5, 4]) };
const corners = [[0, 1, 2], [2, 1, 3], [2, 3, 5], [2, 5, 4]];
const diagonal = (a, b) => (a === 2 && b === 5) || (a === 5 && b === 2);

// The side codes filled for `edges` (vertex pairs) with code 100 + edge index, checked per corner.
function check(edges) {
  const codes = Float32Array.from({ length: edges.length / 2 }, (_, e) => 100 + e);
  const out = new Float32Array(3 * 3 * corners.length);
  fillEdgeCodes(out, mesh, edges, codes, 7);
  const indexOf = (a, b) => {
    for (let e = 0; e < edges.length / 2; e++) if ((edges[2 * e] === a && edges[2 * e + 1] === b) || (edges[2 * e] === b && edges[2 * e + 1] === a)) return e;
    return -1;
  };
  corners.forEach((c, t) => {
    for (let v = 0; v < 3; v++) {
      for (let k = 0; k < 3; k++) {
        const a = c[(k + 1) % 3], b = c[(k + 2) % 3];
        const want = diagonal(a, b) ? NO_EDGE : 100 + indexOf(a, b);
        assert.equal(out[9 * t + 3 * v + k], want, `triangle ${t} vertex ${v}: side opposite corner ${k} (${a}, ${b})`);
      }
    }
  });
  const plain = new Float32Array(out.length);
  fillEdgeCodes(plain, mesh, edges, null, 7);
  assert.deepEqual([...plain], [...out].map((x) => (x === NO_EDGE ? NO_EDGE : 7)));
}

test('each side has its edge\'s code, a quad\'s diagonal none (edges sorted as the core lists them)', () => {
  const edges = uniqueEdges(mesh.triangles, mesh.quads);
  assert.equal(edges.length / 2, 8);
  check(edges);
});

test('the same for edges in another order (reversed list, pairs swapped)', () => {
  const sorted = uniqueEdges(mesh.triangles, mesh.quads), n = sorted.length / 2;
  const edges = new Uint32Array(sorted.length);
  for (let e = 0; e < n; e++) { edges[2 * e] = sorted[2 * (n - 1 - e) + 1]; edges[2 * e + 1] = sorted[2 * (n - 1 - e)]; }
  check(edges);
});

// Page-side fixtures (passed to page.evaluate, so they must be self-contained).

// The surface drag of issue #12 ("Surface p2 with holes"): the radial source dragged, at
// (u, 0), and the metric edit that refines the preset to about 50k triangles.
export const dragSource = (u) => ({ type: 'radial', center: [u, 0], metric: { alpha: 0, h1: 0.15, h2: 0.15 }, radius: 1.5 });
export const refinedP2Metric = { chordTolerance: 0.0025, hmax: 0.3 };

// Runs in the page: a UV sphere with about `target` triangles as a dimension-3 mesh.
export function sphereMesh(target) {
  const nu = Math.round(Math.sqrt(target / 2) * 1.4), nv = Math.max(3, Math.round(target / (2 * nu)));
  const n = nu * (nv + 1);
  const vertices = new Float64Array(3 * n), params = new Float64Array(2 * n), positions = new Float32Array(3 * n);
  for (let j = 0; j <= nv; j++) {
    for (let i = 0; i < nu; i++) {
      const u = (2 * Math.PI * i) / nu, v = (Math.PI * j) / nv;
      const k = j * nu + i;
      const p = [Math.sin(v) * Math.cos(u), Math.sin(v) * Math.sin(u), Math.cos(v)];
      vertices.set(p, 3 * k); positions.set(p, 3 * k); params.set([u, v], 2 * k);
    }
  }
  const tris = [];
  for (let j = 0; j < nv; j++) {
    for (let i = 0; i < nu; i++) {
      const a = j * nu + i, b = j * nu + ((i + 1) % nu), c = a + nu, d = b + nu;
      tris.push(a, b, d, a, d, c);
    }
  }
  window.anisomeshApp.showMesh({ dimension: 3, vertices, params, positions, triangles: Uint32Array.from(tris) });
  return tris.length / 3;
}


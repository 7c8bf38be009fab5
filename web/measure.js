// Mesh measures in the metric of the control space, computed in the worker for the
// colouring and the histograms. They mirror native/src/mesh/quality.cpp (Mt averaged over
// an edge's / element's vertices), so the numbers match the core's quality report.

// Symmetric square root Mt of M = [a b; b c] (SPD): sqrt(M) = (M + s I) / t with
// s = sqrt(det M), t = sqrt(tr M + 2 s).
export function mtFromTensors(m) {
  const n = m.length / 3;
  const mt = new Float64Array(3 * n);
  for (let i = 0; i < n; i++) {
    const a = m[3 * i], b = m[3 * i + 1], c = m[3 * i + 2];
    const s = Math.sqrt(Math.max(a * c - b * b, 0));
    const t = Math.sqrt(a + c + 2 * s) || 1;
    mt[3 * i] = (a + s) / t;
    mt[3 * i + 1] = b / t;
    mt[3 * i + 2] = (c + s) / t;
  }
  return mt;
}

// Smallest requested size per vertex (1 / sqrt of the largest eigenvalue of M), for the lifted 3D view.
export function smallestSizes(m) {
  const n = m.length / 3;
  const h = new Float32Array(n);
  for (let i = 0; i < n; i++) {
    const a = m[3 * i], b = m[3 * i + 1], c = m[3 * i + 2];
    h[i] = 1 / Math.sqrt(0.5 * (a + c) + Math.hypot(0.5 * (a - c), b));
  }
  return h;
}

// Distinct edges of all elements (pairs a < b), sorted like the core does.
export function uniqueEdges(tris, quads) {
  const keys = new Float64Array(tris.length + quads.length);  // 3 per tri, 4 per quad
  let k = 0;
  // a * 2^26 + b is exact in a double for up to 2^26 vertices (67M), enough here.
  const add = (a, b) => { keys[k++] = a < b ? a * 67108864 + b : b * 67108864 + a; };
  for (let t = 0; t < tris.length; t += 3) { add(tris[t], tris[t + 1]); add(tris[t + 1], tris[t + 2]); add(tris[t + 2], tris[t]); }
  for (let q = 0; q < quads.length; q += 4) {
    for (let j = 0; j < 4; j++) add(quads[q + j], quads[q + ((j + 1) & 3)]);
  }
  keys.sort();
  const out = [];
  let prev = -1;
  for (let i = 0; i < keys.length; i++) {
    if (keys[i] === prev) continue;
    prev = keys[i];
    out.push(Math.floor(prev / 67108864), prev % 67108864);
  }
  return Uint32Array.from(out);
}

// Per-edge metric length and per-element metric quality (triangles, then quads).
export function measure(mesh, mt) {
  const uv = mesh.params;
  const tris = mesh.triangles, quads = mesh.quads;
  const edges = uniqueEdges(tris, quads);
  const edgeLength = new Float32Array(edges.length / 2);
  for (let e = 0; e < edgeLength.length; e++) {
    const a = edges[2 * e], b = edges[2 * e + 1];
    const ma = 0.5 * (mt[3 * a] + mt[3 * b]), mb = 0.5 * (mt[3 * a + 1] + mt[3 * b + 1]), mc = 0.5 * (mt[3 * a + 2] + mt[3 * b + 2]);
    const dx = uv[2 * b] - uv[2 * a], dy = uv[2 * b + 1] - uv[2 * a + 1];
    edgeLength[e] = Math.hypot(ma * dx + mb * dy, mb * dx + mc * dy);
  }
  const nt = tris.length / 3, nq = quads.length / 4;
  const quality = new Float32Array(nt + nq);
  const ex = new Float64Array(4), ey = new Float64Array(4);
  const SQRT3 = Math.sqrt(3);
  for (let t = 0; t < nt; t++) {
    const i0 = tris[3 * t], i1 = tris[3 * t + 1], i2 = tris[3 * t + 2];
    const a = (mt[3 * i0] + mt[3 * i1] + mt[3 * i2]) / 3;
    const b = (mt[3 * i0 + 1] + mt[3 * i1 + 1] + mt[3 * i2 + 1]) / 3;
    const c = (mt[3 * i0 + 2] + mt[3 * i1 + 2] + mt[3 * i2 + 2]) / 3;
    const ids = [i0, i1, i2];
    for (let j = 0; j < 3; j++) {
      const p = ids[j], q = ids[(j + 1) % 3];
      const dx = uv[2 * q] - uv[2 * p], dy = uv[2 * q + 1] - uv[2 * p + 1];
      ex[j] = a * dx + b * dy; ey[j] = b * dx + c * dy;
    }
    const cross = ex[0] * -ey[2] - ey[0] * -ex[2];
    const sum = ex[0] * ex[0] + ey[0] * ey[0] + ex[1] * ex[1] + ey[1] * ey[1] + ex[2] * ex[2] + ey[2] * ey[2];
    quality[t] = sum > 0 ? (2 * SQRT3 * cross) / sum : 0;
  }
  for (let q = 0; q < nq; q++) {
    let a = 0, b = 0, c = 0;
    for (let j = 0; j < 4; j++) {
      const v = quads[4 * q + j];
      a += 0.25 * mt[3 * v]; b += 0.25 * mt[3 * v + 1]; c += 0.25 * mt[3 * v + 2];
    }
    let qq = 1;
    for (let j = 0; j < 4; j++) {
      const p = quads[4 * q + j], n1 = quads[4 * q + ((j + 1) & 3)], n2 = quads[4 * q + ((j + 3) & 3)];
      const d1x = uv[2 * n1] - uv[2 * p], d1y = uv[2 * n1 + 1] - uv[2 * p + 1];
      const d2x = uv[2 * n2] - uv[2 * p], d2y = uv[2 * n2 + 1] - uv[2 * p + 1];
      const e1x = a * d1x + b * d1y, e1y = b * d1x + c * d1y, e2x = a * d2x + b * d2y, e2y = b * d2x + c * d2y;
      const sum = e1x * e1x + e1y * e1y + e2x * e2x + e2y * e2y;
      qq = Math.min(qq, sum > 0 ? (2 * (e1x * e2y - e1y * e2x)) / sum : 0);
    }
    quality[nt + q] = qq;
  }
  return { edges, edgeLength, quality };
}


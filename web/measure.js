// Distinct element edges of a mesh the page shows without a case run (showMesh): the
// measures of case runs (edge lengths, qualities, sizes) come from the core's report
// (ElementMeasures), so the page keeps no copy of the core's quality code.

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

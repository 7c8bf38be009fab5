// The mesh's element edges drawn by the faces' own shader, in the same pass as the faces
// (no line primitives): each face fragment knows its distances in pixels to its triangle's
// three sides (barycentric coordinates from gl_VertexID over their screen derivatives) and
// blends the nearest side's colour over the face colour within ~1 pixel of it, as a 1-pixel
// line of that colour and opacity drawn over the face would. A side is a mesh edge (coloured
// by its table row: edge length colours or the plain colour) or nothing (a quad's diagonal).
// On a software rasterizer the line primitives cost more than the faces under them
// (native/bench/mesh_draw_cost.mjs); this draws both for about the faces' price.
import * as THREE from 'three';

export const NO_EDGE = -1;  // the code of a triangle side that is not an element edge

/**
 * Patches material (a mesh material drawing non-indexed triangles with an 'edgeCode'
 * attribute: per vertex, the codes of its triangle's sides opposite corners 0, 1, 2) to
 * draw the edges. table: a DataTexture, one RGB colour per code (linear). Returns the
 * uniforms: edgeOpacity (0: no edges).
 */
export function drawEdgesInFaces(material, table, opacity) {
  const uniforms = { edgeTable: { value: table }, edgeOpacity: { value: opacity } };
  material.onBeforeCompile = (shader) => {
    Object.assign(shader.uniforms, uniforms);
    shader.vertexShader = shader.vertexShader
      .replace('void main() {', `attribute vec3 edgeCode;
flat varying vec3 vEdgeCode;
varying vec3 vCorner;
void main() {
  int corner = gl_VertexID % 3;
  vCorner = vec3(corner == 0, corner == 1, corner == 2);
  vEdgeCode = edgeCode;`);
    shader.fragmentShader = shader.fragmentShader
      .replace('void main() {', `uniform sampler2D edgeTable;
uniform float edgeOpacity;
flat varying vec3 vEdgeCode;
varying vec3 vCorner;
void main() {`)
      // After the conversion to the output's colour space: the blend of a line drawn over
      // the face happens there (sRGB canvas) or in linear (a render target: identity).
      .replace('#include <colorspace_fragment>', `#include <colorspace_fragment>
  {
    vec3 gx = dFdx(vCorner), gy = dFdy(vCorner);
    vec3 d = vCorner / max(sqrt(gx * gx + gy * gy), vec3(1e-9));  // pixels to each side
    d += step(vEdgeCode, vec3(-0.5)) * 1e9;  // sides that are no edge
    float dm = min(d.x, min(d.y, d.z));
    float a = edgeOpacity * clamp(1.0 - dm, 0.0, 1.0);
    if (a > 0.0) {
      float code = dm == d.x ? vEdgeCode.x : (dm == d.y ? vEdgeCode.y : vEdgeCode.z);
      vec3 edge = linearToOutputTexel(vec4(texelFetch(edgeTable, ivec2(int(code + 0.5), 0), 0).rgb, 1.0)).rgb;
      float face = gl_FragColor.a, alpha = 1.0 - (1.0 - face) * (1.0 - a);
      gl_FragColor = vec4((gl_FragColor.rgb * face * (1.0 - a) + edge * a) / alpha, alpha);
    }
  }`);
  };
  material.customProgramCacheKey = () => 'edges-in-faces';
  material.needsUpdate = true;
  return uniforms;
}

/** A one-row float texture of RGB colours (rgb: Float32Array, 3 per code), for drawEdgesInFaces. */
export function edgeColorTable(rgb) {
  const n = rgb.length / 3, data = new Float32Array(4 * n);
  for (let i = 0; i < n; i++) { data[4 * i] = rgb[3 * i]; data[4 * i + 1] = rgb[3 * i + 1]; data[4 * i + 2] = rgb[3 * i + 2]; data[4 * i + 3] = 1; }
  const t = new THREE.DataTexture(data, n, 1, THREE.RGBAFormat, THREE.FloatType);
  t.minFilter = t.magFilter = THREE.NearestFilter;
  t.needsUpdate = true;
  return t;
}

/**
 * Fills out (3 floats per face vertex: triangles, then quads as two triangles (q0 q1 q2),
 * (q0 q2 q3), as the faces are drawn) with each triangle's side codes: codes[e] for the mesh
 * edge e (edges: vertex pairs), or `plain` for every edge when codes is null; NO_EDGE for a
 * quad's diagonal.
 */
export function fillEdgeCodes(out, mesh, edges, codes, plain) {
  const tris = mesh.triangles, quads = mesh.quads;
  const code = codes ? edgeFinder(edges, codes) : () => plain;
  let o = 0;
  // One triangle (corners a, b, c): its sides opposite a, b, c; `diagonal`: the side opposite that corner is none.
  const put = (a, b, c, diagonal) => {
    const x = diagonal === 0 ? NO_EDGE : code(b, c), y = diagonal === 1 ? NO_EDGE : code(c, a), z = diagonal === 2 ? NO_EDGE : code(a, b);
    for (let k = 0; k < 3; k++) { out[o++] = x; out[o++] = y; out[o++] = z; }
  };
  for (let t = 0; t < tris.length; t += 3) put(tris[t], tris[t + 1], tris[t + 2], -1);
  for (let q = 0; q < quads.length; q += 4) {
    put(quads[q], quads[q + 1], quads[q + 2], 1);
    put(quads[q], quads[q + 2], quads[q + 3], 2);
  }
}

// (a, b) -> codes[index of the edge {a, b} in edges]: the edges as the core lists them
// (sorted by smaller end, then larger) through each smaller end's run, else a map.
function edgeFinder(edges, codes) {
  const ne = edges.length / 2;
  let nv = 0, sorted = true;
  for (let e = 0; e < ne; e++) {
    const a = edges[2 * e], b = edges[2 * e + 1];
    if (b > nv) nv = b;
    if (a >= b || (e > 0 && (a < edges[2 * e - 2] || (a === edges[2 * e - 2] && b <= edges[2 * e - 1])))) sorted = false;
  }
  if (!sorted) {
    const map = new Map();
    for (let e = 0; e < ne; e++) {
      const a = edges[2 * e], b = edges[2 * e + 1];
      map.set(a < b ? a * 4294967296 + b : b * 4294967296 + a, codes[e]);
    }
    return (a, b) => map.get(a < b ? a * 4294967296 + b : b * 4294967296 + a) ?? NO_EDGE;
  }
  const first = new Int32Array(nv + 2);
  for (let e = 0; e < ne; e++) first[edges[2 * e] + 1]++;
  for (let v = 0; v <= nv; v++) first[v + 1] += first[v];
  return (a, b) => {
    const lo = a < b ? a : b, hi = a < b ? b : a;
    if (lo > nv) return NO_EDGE;
    for (let e = first[lo], end = first[lo + 1]; e < end; e++) if (edges[2 * e + 1] === hi) return codes[e];
    return NO_EDGE;
  };
}

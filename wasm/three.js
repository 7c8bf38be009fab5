// three.js helpers (export 'anisomesh/three'): display objects for meshes and control
// spaces. three is a peer dependency: this module imports it, the core does not.
import * as THREE from 'three';

/** A BufferGeometry of the mesh's triangles (quads split in two), Float32 positions. */
export function meshGeometry(mesh) {
  const geometry = new THREE.BufferGeometry();
  const positions = mesh.positions ?? toXyz(mesh);
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  const tris = mesh.triangles ?? new Uint32Array(0), quads = mesh.quads ?? new Uint32Array(0);
  const index = new Uint32Array(tris.length + (quads.length / 4) * 6);
  index.set(tris);
  for (let q = 0, o = tris.length; q < quads.length; q += 4, o += 6) {
    index.set([quads[q], quads[q + 1], quads[q + 2], quads[q], quads[q + 2], quads[q + 3]], o);
  }
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  return geometry;
}

/** LineSegments of every element edge (each edge once). */
export function meshEdges(mesh, material = new THREE.LineBasicMaterial({ color: 0x1b3a5c })) {
  const positions = mesh.positions ?? toXyz(mesh);
  const seen = new Set(), pairs = [];
  const add = (a, b) => {
    const key = a < b ? a * 4294967296 + b : b * 4294967296 + a;
    if (!seen.has(key)) { seen.add(key); pairs.push(a, b); }
  };
  const t = mesh.triangles ?? [], q = mesh.quads ?? [];
  for (let i = 0; i < t.length; i += 3) { add(t[i], t[i + 1]); add(t[i + 1], t[i + 2]); add(t[i + 2], t[i]); }
  for (let i = 0; i < q.length; i += 4) for (let k = 0; k < 4; k++) add(q[i + k], q[i + ((k + 1) % 4)]);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(pairs);
  return new THREE.LineSegments(geometry, material);
}

/** LineSegments of a control space's cells (quadtree leaves or background triangles) from ControlSpace.inspect(). */
export function controlSpaceCells(inspect, material = new THREE.LineBasicMaterial({ color: 0x888888 })) {
  const pts = [];
  const nodes = inspect.nodes ?? [];
  for (const cell of inspect.cells ?? []) {
    for (let k = 0; k < cell.length; k++) {
      const a = nodes[cell[k]].p, b = nodes[cell[(k + 1) % cell.length]].p;
      pts.push(a[0], a[1], 0, b[0], b[1], 0);
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(pts), 3));
  return new THREE.LineSegments(geometry, material);
}

/**
 * LineSegments of the unit ellipses of a control space's nodes (from inspect()), scaled by
 * `scale` (ellipses of neighbouring nodes overlap at 1), `segments` per ellipse.
 */
export function metricEllipses(inspect, { scale = 0.5, segments = 24, material = new THREE.LineBasicMaterial({ color: 0xc0392b }) } = {}) {
  const nodes = inspect.nodes ?? inspect.samples ?? [];
  const pts = new Float32Array(nodes.length * segments * 6);
  let o = 0;
  for (const n of nodes) {
    const c = Math.cos(n.alpha), s = Math.sin(n.alpha);
    for (let k = 0; k < segments; k++) {
      for (const j of [k, k + 1]) {
        const t = (2 * Math.PI * j) / segments;
        const u = scale * n.h1 * Math.cos(t), v = scale * n.h2 * Math.sin(t);
        pts[o++] = n.p[0] + c * u - s * v;
        pts[o++] = n.p[1] + s * u + c * v;
        pts[o++] = 0;
      }
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(pts, 3));
  return new THREE.LineSegments(geometry, material);
}

function toXyz(mesh) {
  const d = mesh.dimension, v = mesh.vertices, n = v.length / d;
  const out = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) for (let k = 0; k < d; k++) out[3 * i + k] = v[d * i + k];
  return out;
}

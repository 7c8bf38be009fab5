// 'anisomesh/three' types compile against @types/three (the optional peer).
import type { BufferGeometry, LineSegments } from 'three';
import { meshGeometry, meshEdges } from 'anisomesh/three';
import type { MeshArrays } from 'anisomesh';

export function build(mesh: MeshArrays): [BufferGeometry, LineSegments] {
  return [meshGeometry(mesh), meshEdges(mesh)];
}

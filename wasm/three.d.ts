// Types of 'anisomesh/three': three.js display objects for anisomesh results.
import type { BufferGeometry, LineSegments, Material } from 'three';
import type { MeshArrays } from './index.js';

/** A BufferGeometry of the mesh's triangles (quads split in two), Float32 positions. */
export function meshGeometry(mesh: MeshArrays): BufferGeometry;
/** LineSegments of every element edge (each edge once). */
export function meshEdges(mesh: MeshArrays, material?: Material): LineSegments;
/** LineSegments of a control space's cells, from ControlSpace.inspect(). */
export function controlSpaceCells(inspect: Record<string, unknown>, material?: Material): LineSegments;
/** LineSegments of the nodes' unit ellipses (scaled), from ControlSpace.inspect(). */
export function metricEllipses(
  inspect: Record<string, unknown>,
  options?: { scale?: number; segments?: number; material?: Material },
): LineSegments;

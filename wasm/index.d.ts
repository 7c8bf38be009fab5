// Hand-written types of the anisomesh package.

/** Stable error codes of the core, shared by native and JS. */
export type AnisomeshErrorCode =
  | 'INVALID_ARGUMENT'
  | 'INVALID_METRIC'
  | 'INVALID_DOMAIN'
  | 'OPEN_CONTOUR'
  | 'SELF_INTERSECTING_CONTOUR'
  | 'HOLE_OUTSIDE_DOMAIN'
  | 'ZERO_LENGTH_CURVE'
  | 'INVALID_SURFACE'
  | 'ELEMENT_BUDGET_EXCEEDED'
  | 'PARSE_ERROR'
  | 'IO_ERROR'
  | 'CANCELLED'
  | 'OUT_OF_MEMORY'
  | 'INTERNAL';

/** Thrown by every call that fails. The module stays usable afterwards. */
export class AnisomeshError extends Error {
  readonly name: 'AnisomeshError';
  readonly code: AnisomeshErrorCode;
  constructor(code: AnisomeshErrorCode, message: string);
}

/**
 * A metric, given in any one of three forms:
 * sizes (h1 along the direction at angle alpha in radians, h2 along its normal),
 * an isotropic size h, or the tensor components m11, m12, m22.
 */
export type MetricSpec =
  | { alpha?: number; h1: number; h2: number }
  | { h: number }
  | { m11: number; m12: number; m22: number };

/** A metric in all its forms: tensor M, transformation matrix Mt (M = Mt Mt^T), sizes with h1 <= h2. */
export interface Metric {
  m11: number;
  m12: number;
  m22: number;
  t11: number;
  t12: number;
  t22: number;
  /** Direction of h1 (the smaller size), in (-pi/2, pi/2]. */
  alpha: number;
  h1: number;
  h2: number;
}

export type Vec2 = readonly [number, number] | Float64Array;

/**
 * A mesh as typed arrays. Connectivity is 0-based. `vertices` holds `dimension` values per
 * vertex, `params` the parameter coordinates (u, v) (= x, y for planar meshes) and
 * `positions` Float32 x, y, z ready for a three.js BufferAttribute.
 */
export interface MeshArrays {
  dimension: 2 | 3;
  vertices: Float64Array;
  params?: Float64Array;
  positions?: Float32Array;
  triangles?: Uint32Array;
  quads?: Uint32Array;
  edges?: Uint32Array;
  vertexRefs?: Int32Array;
  triangleRefs?: Int32Array;
  quadRefs?: Int32Array;
  edgeRefs?: Int32Array;
}

/** A JSON case (examples/CASE_FORMAT.md): domain, controlSpace, sources, options. */
export type Case = Record<string, unknown>;

/** The quality report of a mesh, measured in the metric it was asked to follow. */
export interface MeshStats {
  vertices: number;
  triangles: number;
  quads: number;
  edges: number;
  inverted: number;
  degenerate: number;
  [key: string]: unknown;
}

export interface CaseResult {
  mesh: MeshArrays;
  /** The quality report; null for a planar run with stats: false (see caseStats()). */
  stats: MeshStats | null;
  /** The control space's nodes and cells (with inspectControlSpace), else null. */
  controlSpace: Record<string, unknown> | null;
  /** Planar cases with vertexMetrics: the final control space's m11, m12, m22 at every vertex, else null. */
  vertexMetrics: Float64Array | null;
  /**
   * With measures: the distinct element edges (a < b pairs), and for planar cases the metric
   * length of each edge, the metric quality of each element (triangles, then quads) and the
   * smallest requested size at each vertex, measured as the quality report measures them.
   */
  measures?: { edges: Uint32Array; edgeLength?: Float32Array; quality?: Float32Array; vertexH?: Float32Array };
  /** Milliseconds spent in the core: the case run, copying the results out, the measures. */
  timings: { runMs: number; outputMs: number; measuresMs: number };
}

/** A control space kept alive in the core: free it with dispose() (a FinalizationRegistry is only a safety net). */
export interface ControlSpace {
  metricAt(p: Vec2): { m11: number; m12: number; m22: number };
  /** Metrics at x, y pairs: m11, m12, m22 per point. */
  metricsAt(xy: Float64Array): Float64Array;
  /** Nodes (positions, metrics, sizes) and cells (quadtree leaves or triangles). */
  inspect(options?: { sampleGrid?: number }): Record<string, unknown>;
  /** Legacy VTK text for ParaView (adaptive structures only). */
  toVtk(): string;
  dispose(): void;
}

export type MeshFormat = 'mesh' | 'vtk' | 'obj';

export interface MeshCaseOptions {
  /** Also return the final control space's nodes and cells (planar cases). */
  inspectControlSpace?: boolean;
  /** Also return the final control space's metric at every vertex (planar cases). */
  vertexMetrics?: boolean;
  /** Also return per-edge lengths and per-element qualities (CaseResult.measures). */
  measures?: boolean;
  /** Planar cases: false skips the quality report (stats is null); caseStats() computes it after. */
  stats?: boolean;
  /** Override the case's options.quads / options.allQuads. */
  quads?: boolean;
  allQuads?: boolean;
  /** Element budget (ELEMENT_BUDGET_EXCEEDED above it); overrides options.maxElements. */
  maxElements?: number;
  /** Planar cases: run the paper's section 3.2 control-space update loop (default true). */
  controlSpaceUpdates?: boolean;
  /** Progress in [0, 1]; return false to cancel. */
  onProgress?: (fraction: number) => boolean | void;
}

export interface Anisomesh {
  /** Version of the WebAssembly core. */
  readonly version: string;
  /** Bytes malloc has in use in the wasm heap and the heap's size, for leak checks. */
  memoryStats(): { inUseBytes: number; heapBytes: number };
  /** Validates a metric and returns all its forms. Throws INVALID_METRIC for NaN, non-positive sizes or a non-SPD tensor. */
  metric(spec: MetricSpec): Metric;
  /** Metric intersection (the paper's min(M1, M2)): the largest unit ellipse inside both. */
  intersectMetrics(a: MetricSpec, b: MetricSpec): Metric;
  /** Interpolates the transformation matrices: (1 - t) Mt_a + t Mt_b, t in [0, 1]. */
  interpolateMetrics(a: MetricSpec, b: MetricSpec, t: number): Metric;
  /** Metric length sqrt(v^T M v) of the vector v. */
  metricLength(metric: MetricSpec, v: Vec2): number;
  /** The largest relative change of requested length between two metrics over all directions (0 when equal). */
  metricDifference(a: MetricSpec, b: MetricSpec): number;
  /** The unit ellipse of a metric around center: a closed polyline as xy pairs. */
  metricEllipse(metric: MetricSpec, center?: Vec2, segments?: number): Float64Array;
  /**
   * Meshes a JSON case, planar (examples/CASE_FORMAT.md) or surface (examples/SURFACE_FORMAT.md),
   * given as an object or JSON text. onProgress(fraction) is called while meshing; returning
   * false cancels the run with AnisomeshError CANCELLED.
   */
  meshCase(c: Case | string, options?: MeshCaseOptions): CaseResult;
  /** The quality report of the last planar meshCase run made with { stats: false }. */
  caseStats(): MeshStats;
  /** Remeshes the domain bounded by mesh's boundary edges under per-vertex tensors (m11, m12, m22 each). */
  remesh(
    mesh: MeshArrays,
    metrics: Float64Array,
    options?: { hmin?: number; hmax?: number; hgrad?: number; maxElements?: number },
  ): { mesh: MeshArrays; stats: Record<string, unknown> };
  /** The mesh as text in a file format ('svg' for a picture of a planar mesh). */
  writeMesh(mesh: MeshArrays, format?: MeshFormat | 'svg'): string;
  /** Parses mesh text. */
  readMesh(text: string, format?: MeshFormat): MeshArrays;
  /** Parses a Medit .sol (scalar sizes or tensors): m11, m12, m22 per vertex. */
  readSol(text: string, vertexCount: number): Float64Array;
  /** Writes per-vertex tensors (m11, m12, m22 each) as a Medit .sol. */
  writeSol(metrics: Float64Array): string;
  /** Evaluates an expression in u, v or in options.variables (throws PARSE_ERROR naming the column on bad input). */
  evaluateExpression(text: string, u?: number, v?: number, options?: { variables?: [string, string] }): number;
  /** Builds a case's control space (its controlSpace, sources and domain). */
  createControlSpace(c: Case | string): ControlSpace;
  /**
   * The exact minimum (metric intersection) of two or more control spaces, evaluated at each
   * query: its unit ellipse lies inside every input's. The inputs stay owned by the caller
   * (disposing them does not invalidate the result); inspect() samples it on a grid; toVtk()
   * throws (it has no structure of its own).
   */
  minimumControlSpace(...spaces: ControlSpace[]): ControlSpace;
}

/** Loads the WebAssembly core (once; later calls return the same instance). */
export function loadAnisomesh(): Promise<Anisomesh>;

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
  | 'INTERNAL'
  /** JS only: the .wasm could not be fetched or instantiated (loadAnisomesh; retrying is allowed). */
  | 'WASM_LOAD_FAILED';

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

export type Point2 = readonly [number, number];
export type Point3 = readonly [number, number, number];

/** A metric in a case: size h1 along the direction at angle alpha (radians, default 0), h2 across (default h1). */
export interface CaseMetric {
  alpha?: number;
  h1: number;
  h2?: number;
}

interface CurveCommon {
  /** Medit reference of the boundary edges (default 1 outer, k + 2 for holes[k]). */
  ref?: number;
  reversed?: boolean;
}
/** A boundary curve (examples/CASE_FORMAT.md, "Curves"). */
export type Curve =
  | (CurveCommon & { type: 'line'; p1: Point2; p2: Point2 })
  | (CurveCommon & { type: 'arc'; center: Point2; radius: number; start: number; end: number })
  | (CurveCommon & { type: 'arc'; points: readonly [Point2, Point2, Point2] })
  | (CurveCommon & { type: 'circle'; center: Point2; radius: number })
  | (CurveCommon & { type: 'polyline'; points: readonly Point2[] })
  | (CurveCommon & { type: 'bezier'; points: readonly [Point2, Point2, Point2, Point2] })
  | (CurveCommon & { type: 'bspline'; points: readonly Point2[] });

/** A metric source in the plane (planar cases) or in a patch's (u, v) plane (radial, segment, polyline). */
export type Source =
  | { type: 'radial'; center: Point2; metric: CaseMetric; radius: number }
  | { type: 'segment'; p1: Point2; p2: Point2; metric: CaseMetric; radius: number }
  | { type: 'polyline'; points: readonly Point2[]; metric: CaseMetric; radius: number }
  | { type: 'nodes'; points: readonly Point2[]; metrics: readonly CaseMetric[] }
  | { type: 'analytic'; field: 'boundary_layer'; p1: Point2; p2: Point2; h0: number; hTangent: number; thickness: number }
  | { type: 'analytic'; field: 'shear_layer_circle'; center: Point2; radius: number; h0: number; hTangent: number; thickness: number }
  | { type: 'analytic'; field: 'point'; center: Point2; h0: number; growth: number }
  | { type: 'analytic'; field: 'expression'; h1: string | number; alpha?: string | number; h2?: string | number };

/** A planar case (examples/CASE_FORMAT.md). */
export interface PlanarCase {
  name?: string;
  description?: string;
  domain: { outer: readonly Curve[]; holes?: readonly (readonly Curve[])[] };
  controlSpace: {
    kind?: 'quadtree' | 'background';
    hmin?: number;
    hmax: number;
    /** dr >= 1; null or absent: no gradation smoothing. */
    gradation?: number | null;
    interpolation?: 'bilinear' | 'serendipity' | 'linear' | 'inverse_distance';
    refineThreshold?: number;
    maxLevel?: number;
  };
  sources?: readonly Source[];
  options?: { quads?: boolean; allQuads?: boolean; maxElements?: number };
  /** Planar cases have no patches: this is what tells the two kinds apart. */
  patches?: never;
}

/** A parametric surface (examples/SURFACE_FORMAT.md, "Surfaces"); domain [[u0, u1], [v0, v1]] where given. */
export type Surface =
  | { type: 'expression'; x: string; y: string; z: string; domain: readonly [Point2, Point2] }
  | { type: 'heightfield'; z: string; domain: readonly [Point2, Point2] }
  | { type: 'p2'; domain?: readonly [Point2, Point2] }
  | { type: 'plane'; origin?: Point3; a1?: Point3; a2?: Point3; domain?: readonly [Point2, Point2] }
  | { type: 'sphere'; radius?: number; center?: Point3; domain?: readonly [Point2, Point2] }
  | { type: 'cylinder'; radius?: number; center?: Point3; domain?: readonly [Point2, Point2] }
  | { type: 'torus'; majorRadius?: number; minorRadius?: number; center?: Point3; domain?: readonly [Point2, Point2] }
  | { type: 'bezier'; points: readonly (readonly Point3[])[]; domain?: readonly [Point2, Point2] };

/** One patch of a surface case: a surface (or the name of one in surfaces) and its (u, v) domain. */
export interface Patch {
  name?: string;
  id?: number;
  surface: Surface | string;
  outer?: readonly Curve[];
  holes?: readonly (readonly Curve[])[];
  sources?: readonly Extract<Source, { type: 'radial' | 'segment' | 'polyline' }>[];
}

/** A curve of a patch's contour: contour 0 is the outer one, k + 1 holes[k]. */
export interface CurveRef {
  patch: string | number;
  contour?: number;
  curve: number;
}

/** A surface case (examples/SURFACE_FORMAT.md). */
export interface SurfaceCase {
  name?: string;
  description?: string;
  metric?: {
    chordTolerance?: number;
    chordSafety?: number;
    angleTolerance?: number;
    hmin?: number;
    hmax?: number;
    maxAspectRatio?: number;
    gradation?: number | null;
    contourCurvature?: boolean;
  };
  adaptation?: boolean;
  options?: { maxElements?: number; maxRounds?: number; improvementPasses?: number; quads?: boolean; allQuads?: boolean };
  surfaces?: Record<string, Surface>;
  patches: readonly Patch[];
  shared?: readonly { a: CurveRef; b: CurveRef; reversed?: boolean }[];
  sources3d?: readonly { type: 'radial'; center: Point3; h: number; radius: number }[];
}

/** A JSON case: planar (no "patches") or surface (with "patches"). */
export type Case = PlanarCase | SurfaceCase;

/** Edge metric lengths of a report (unit length: the requested size). */
export interface EdgeLengthStats {
  min: number;
  max: number;
  mean: number;
  /** Fraction of edges of metric length in [1/sqrt2, sqrt2]. */
  fractionWithinSqrt2: number;
}

/** The quality report of a planar case or a remesh run, measured in the final control space. */
export interface PlanarMeshStats {
  vertices: number;
  triangles: number;
  quads: number;
  /** Distinct element edges. */
  edges: number;
  inverted: number;
  degenerate: number;
  boundaryLoops: number;
  boundaryPoints: number;
  controlNodes: number;
  controlElements: number;
  largestNeighbourSizeRatio: number;
  edgeLength: EdgeLengthStats & { 'fractionWithin0.6_1.3': number };
  quality: {
    min: number;
    mean: number;
    triangleMin: number;
    triangleMean: number;
    quadMin: number;
    quadMean: number;
    /** Ten bins of metric quality over [0, 1]. */
    histogram: number[];
  };
  /** Section 3.2 control-space updates. */
  boundaryUpdates: {
    rounds: number;
    converged: boolean;
    invalidSegments: number;
    shortSegments: number;
    chordSources: number;
    proximitySources: number;
    refinedElements: number;
    maxChordDeviation: number;
    shortSegmentSources: number;
    rediscretizedContours: number;
  };
  pipelineSeconds: Record<string, number>;
  timings: Record<string, number>;
  notes: string[];
}

/** The quality report of a surface case, measured in 3D (patches, Algorithm 1's rounds). */
export interface SurfaceMeshStats {
  vertices: number;
  triangles: number;
  quads: number;
  inverted: number;
  patches: number;
  patchTriangles: number[];
  rounds: number;
  sharedEdges: number;
  invalidations: number;
  /** Section 3.2 updates over all rounds (the same rules as planar cases). */
  boundaryUpdates: { converged: boolean; chordSources: number; proximitySources: number; shortSegmentSources: number };
  crossSharedSizeRatioMax: number;
  edgeLength: EdgeLengthStats;
  quality: { min: number; mean: number };
  quality3d: {
    edges: number;
    inverted: number;
    qualityMin: number;
    qualityMean: number;
    edgeLengthMin: number;
    edgeLengthMax: number;
    edgeLengthMean: number;
    edgesWithinSqrt2: number;
    chordDeviationMax: number;
    chordDeviationMaxRelative: number;
    edgeChordDeviationMax: number;
    isoChordDeviationMax: number;
  };
  controlSpaceQueries: number;
  controlSpaceSeconds: number;
  curvatureEvaluations: number;
  curvatureSeconds: number;
  secondsTotal: number;
}

/** The quality report of a mesh: planar or surface (tell them apart with 'patches' in stats). */
export type MeshStats = PlanarMeshStats | SurfaceMeshStats;

/**
 * Ellipses of the final control spaces of a surface case, at control elements inside
 * each patch (half the requested sizes along the axes): glyph g has the points
 * offsets[g] .. offsets[g + 1] - 1, in its patch's (u, v) (uv) and mapped to 3D (xyz).
 */
export interface ControlSpaceGlyphs {
  patch: Int32Array;
  offsets: Int32Array;
  uv: Float64Array;
  xyz: Float32Array;
}

export interface CaseResult<S extends MeshStats = MeshStats> {
  mesh: MeshArrays;
  /** The quality report; null for a run with stats: false (see report()). */
  stats: S | null;
  /**
   * Runs with stats: false: the quality report of this run, made now (once; the kept run is
   * freed after it). Lets a caller draw the mesh first and show the report after. A surface
   * run makes its 3D measures here (chord deviations, ...; the per-element ones of measures
   * come with the mesh).
   */
  report?(): S;
  /**
   * Surface runs with stats: false and elementMeasures: false: the per-element 3D quality
   * and per-edge 3D metric length (as measures has them otherwise), made now; call it before
   * report(), which frees the run.
   */
  elementMeasures?(): { quality: Float32Array; edgeLength: Float32Array };
  /** Runs with stats: false: frees the kept run without a report (report() then throws). */
  dispose?(): void;
  /** With options.svg: the .svg picture (as the CLI draws it). */
  svg?: string;
  /** With options.vtu: the .vtu text (VTK XML, as the CLI writes it). */
  vtu?: string;
  /** The control space's nodes and cells (with inspectControlSpace), else null. */
  controlSpace: Record<string, unknown> | null;
  /** Planar cases with vertexMetrics: the final control space's m11, m12, m22 at every vertex, else null. */
  vertexMetrics: Float64Array | null;
  /**
   * With measures: the distinct element edges (a < b pairs), and for planar cases the metric
   * length of each edge, the metric quality of each element (triangles, then quads) and the
   * smallest requested size at each vertex, measured as the quality report measures them;
   * for surface cases the 3D metric quality of each element (the report's quality3d).
   */
  measures?: MeshMeasures;
  /** Surface cases with controlSpaceGlyphs: the final per-patch control spaces drawn as ellipses. */
  glyphs?: ControlSpaceGlyphs;
  /** Surface cases with patchParams: the patch index of each element (triangles, then quads). */
  elementPatch?: Int32Array;
  /** Surface cases with patchParams: (u, v) of each element corner in its own patch (3 per triangle, then 4 per quad). */
  cornerParams?: Float64Array;
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

/** Per-item measures of a mesh (meshCase and adapt with measures: true). */
export interface MeshMeasures {
  /** Distinct element edges (a < b pairs). */
  edges: Uint32Array;
  /** Metric length of each edge (planar runs). */
  edgeLength?: Float32Array;
  /** Metric quality of each element, triangles then quads (planar runs; 3D for surfaces). */
  quality?: Float32Array;
  /** Smallest requested size at each vertex (planar runs). */
  vertexH?: Float32Array;
}

/** Options of adapt() and metricFromField(): exactly one of err or nv. */
export interface AdaptOptions {
  /** Error level: M = 2 c |H| / err (c = 2/9). */
  err?: number;
  /** err relative to the field's range. */
  relative?: boolean;
  /** Target vertex count (L^p continuous-mesh metric). */
  nv?: number;
  norm?: 1 | 2 | 'inf';
  shape?: 'anisotropic' | 'isotropic' | 'uniform';
  hmin?: number;
  hmax?: number;
  anisomax?: number;
  /** Gradation ratio dr of the control space (0: off). */
  hgrad?: number;
  iterations?: number;
  maxElements?: number;
  /** adapt(): also return the last mesh's measures in the last control space. */
  measures?: boolean;
}

/** One adaptation iteration's figures (errorLinf/errorL2 for expression fields only). */
export interface AdaptIteration {
  vertices: number;
  triangles: number;
  complexity: number;
  expectedVertices: number;
  estimatedError: number;
  errorLinf?: number;
  errorL2?: number;
  seconds: number;
}

/** 'msh': Gmsh 4.1 ASCII, 'msh2': Gmsh 2.2 ASCII (readMesh takes either as 'msh'). */
export type MeshFormat = 'mesh' | 'vtk' | 'obj' | 'msh' | 'msh2';
/** Binary Medit (libMeshb, as MMG reads and writes it): bytes, not text. */
export type BinaryMeshFormat = 'meshb';

export interface MeshCaseOptions {
  /** Also return the final control space's nodes and cells (planar cases). */
  inspectControlSpace?: boolean;
  /** Also return the final control space's metric at every vertex (planar cases). */
  vertexMetrics?: boolean;
  /** Also return per-edge lengths and per-element qualities (CaseResult.measures). */
  measures?: boolean;
  /**
   * Surface cases with stats: false and measures: false here leaves measures.quality and
   * measures.edgeLength out (the distinct edges stay) for the result's elementMeasures():
   * the mesh comes sooner (default true).
   */
  elementMeasures?: boolean;
  /**
   * false skips the quality report (stats is null); the result's report() makes it after
   * (surface cases: with the 3D measures it needs, so the mesh comes sooner).
   */
  stats?: boolean;
  /** Override the case's options.quads / options.allQuads. */
  quads?: boolean;
  allQuads?: boolean;
  /** Element budget (ELEMENT_BUDGET_EXCEEDED above it); overrides options.maxElements. */
  maxElements?: number;
  /** Planar cases: run the paper's section 3.2 control-space update loop (default true). */
  controlSpaceUpdates?: boolean;
  /** Surface cases: also return CaseResult.glyphs (the final control spaces drawn). */
  controlSpaceGlyphs?: boolean;
  /** Surface cases: also return CaseResult.elementPatch and CaseResult.cornerParams. */
  patchParams?: boolean;
  /** Progress in [0, 1]; return false to cancel. */
  onProgress?: (fraction: number) => boolean | void;
  /** Also return the .svg picture (CaseResult.svg), drawn as the CLI draws it. */
  svg?: boolean | SvgOptions;
  /** Also return the .vtu text (CaseResult.vtu) with metric, size, quality and edge-length fields. */
  vtu?: boolean;
}

/** How the .svg picture is drawn (the CLI's --svg-uv, --svg-view, --svg-control-space). */
export interface SvgOptions {
  /** Surfaces in the parameter plane instead of a 3D view. */
  uv?: boolean;
  /** 3D view [azimuth, elevation] in degrees (default [-63, 34]). */
  view?: readonly [number, number];
  /** Surfaces: the control spaces' metric ellipses over the mesh. */
  controlSpace?: boolean;
}

export interface RemeshOptions {
  hmin?: number;
  hmax?: number;
  /** Gradation ratio >= 1 (0: off). */
  hgrad?: number;
  /** With metrics null: isotropic size everywhere (MMG's -hsiz); without it, the input's edge lengths. */
  hsiz?: number;
  maxElements?: number;
  onProgress?: (fraction: number) => boolean | void;
  /**
   * Called as each stage starts: 'boundary', 'control space', 'discretization', 'meshing' (the
   * CLI's -v 1 stages), then 'output' (the results copied out of the core). Returning false
   * cancels the run (AnisomeshError CANCELLED). An exception it throws cancels the run too and
   * is thrown by remesh once the core has stopped (as for onProgress).
   */
  onStage?: (stage: string) => boolean | void;
  /**
   * false skips the quality report (stats is null; the CLI makes none without --stats): the
   * result's report() makes it later, dispose() frees the kept run without it.
   */
  stats?: boolean;
  svg?: boolean;
  vtu?: boolean;
}

/** Options of loadAnisomesh: where the .wasm comes from (default: the packaged file). */
export interface LoadOptions {
  /** URL of anisomesh-core.wasm (e.g. copied to a public folder). */
  wasmUrl?: string | URL;
  /** The bytes of anisomesh-core.wasm. */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /**
   * 'anisomesh/threads' only (the single-threaded module ignores it): the most threads the
   * instance will run, 2 to 8, which sizes its worker pool (threads - 1 Web Workers or
   * worker_threads). Default: one worker per core beside the caller, 2 to 7.
   */
  threads?: number;
}

export interface Anisomesh {
  /** Version of the WebAssembly core. */
  readonly version: string;
  /** Bytes malloc has in use in the wasm heap and the heap's size, for leak checks. */
  memoryStats(): { inUseBytes: number; heapBytes: number };
  /**
   * Sets the threads of the core's parallel stages (remesh reading, control space, domain
   * parts, report) and returns the count in effect: always 1 from 'anisomesh'; from
   * 'anisomesh/threads' up to the caller and its worker pool (one worker per core, 2 to 7).
   * The mesh is the same for any count.
   */
  setThreads(threads: number): number;
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
   * false cancels the run with AnisomeshError CANCELLED; an exception it throws cancels the
   * run too and is thrown by meshCase once the core has stopped.
   */
  meshCase(c: PlanarCase, options?: MeshCaseOptions): CaseResult<PlanarMeshStats>;
  meshCase(c: SurfaceCase, options?: MeshCaseOptions): CaseResult<SurfaceMeshStats>;
  meshCase(c: Case | string, options?: MeshCaseOptions): CaseResult;
  /** Remeshes the domain bounded by mesh's boundary edges under per-vertex tensors (m11, m12, m22 each). */
  remesh(
    mesh: MeshArrays,
    /** m11, m12, m22 per vertex; null: isotropic sizes (options.hsiz, else the input's edge lengths). */
    metrics: Float64Array | null,
    options: RemeshOptions & { stats: false },
  ): { mesh: MeshArrays; stats: null; report(): PlanarMeshStats; dispose(): void; svg?: string; vtu?: string };
  remesh(
    mesh: MeshArrays,
    /** m11, m12, m22 per vertex; null: isotropic sizes (options.hsiz, else the input's edge lengths). */
    metrics: Float64Array | null,
    options?: RemeshOptions,
  ): { mesh: MeshArrays; stats: PlanarMeshStats; svg?: string; vtu?: string };
  /** The metric of fields (one value per vertex each) on a planar mesh: m11, m12, m22 per vertex. */
  metricFromField(
    mesh: MeshArrays,
    fields: Float64Array | Float64Array[],
    options: AdaptOptions,
  ): { metrics: Float64Array; complexity: number; expectedVertices: number; hmin: number; hmax: number };
  /**
   * Adapts a planar mesh to fields: values per vertex (transferred between iterations) or
   * expressions in x, y (re-sampled on each mesh; the iterations then report the errors).
   */
  adapt(
    mesh: MeshArrays,
    fields: Float64Array | Float64Array[] | string | string[],
    options: AdaptOptions,
  ): { mesh: MeshArrays; fields: Float64Array[]; iterations: AdaptIteration[]; measures?: MeshMeasures };
  /** The mesh as text in a file format ('svg' for a picture of a planar mesh). */
  writeMesh(mesh: MeshArrays, format?: MeshFormat | 'svg'): string;
  /** The mesh as a binary Medit .meshb file. */
  writeMesh(mesh: MeshArrays, format: BinaryMeshFormat): Uint8Array;
  /** Parses mesh text, as a string or as its UTF-8 bytes (a file read without decoding). */
  readMesh(text: string | Uint8Array, format?: MeshFormat): MeshArrays;
  /** Parses the bytes of a binary Medit .meshb file. */
  readMesh(bytes: Uint8Array, format: BinaryMeshFormat): MeshArrays;
  /** Parses a Medit .sol (scalar sizes or tensors): m11, m12, m22 per vertex. */
  readSol(text: string | Uint8Array, vertexCount: number): Float64Array;
  /** Writes per-vertex tensors (m11, m12, m22 each) as a Medit .sol. */
  writeSol(metrics: Float64Array): string;
  /** Evaluates an expression in u, v or in options.variables (throws PARSE_ERROR naming the column on bad input). */
  evaluateExpression(text: string, u?: number, v?: number, options?: { variables?: [string, string] }): number;
  /**
   * A planar case's domain from an SVG drawing: closed paths (lines, arcs, quadratic and cubic
   * Beziers), polygons, rects, circles, ellipses; the outermost shape is the outer contour, the
   * shapes inside it holes; scaled so the larger side is options.size (default 1), y flipped
   * unless options.flipY is false. Throws PARSE_ERROR, OPEN_CONTOUR or INVALID_DOMAIN.
   */
  domainFromSvg(text: string, options?: { size?: number; flipY?: boolean }): { outer: unknown[]; holes: unknown[][] };
  /**
   * Builds a case's control space (its controlSpace, sources and domain); for a surface case
   * the initial control space of patch options.patch (default 0) in its (u, v) plane.
   */
  createControlSpace(c: Case | string, options?: { patch?: number }): ControlSpace;
  /**
   * The exact minimum (metric intersection) of two or more control spaces, evaluated at each
   * query: its unit ellipse lies inside every input's. The inputs stay owned by the caller
   * (disposing them does not invalidate the result); inspect() samples it on a grid; toVtk()
   * throws (it has no structure of its own).
   */
  minimumControlSpace(...spaces: ControlSpace[]): ControlSpace;
}

/**
 * Loads the WebAssembly core (cached per source: later calls return the same instance). A
 * failed load rejects with AnisomeshError 'WASM_LOAD_FAILED' and is not cached.
 */
export function loadAnisomesh(options?: LoadOptions): Promise<Anisomesh>;

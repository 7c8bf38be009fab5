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

export interface Anisomesh {
  /** Version of the WebAssembly core. */
  readonly version: string;
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
}

/** Loads the WebAssembly core (once; later calls return the same instance). */
export function loadAnisomesh(): Promise<Anisomesh>;

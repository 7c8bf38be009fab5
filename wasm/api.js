// The JavaScript face of anisomesh, shared by the Node and browser entry points.
// It hides embind: plain objects in, plain objects and typed arrays out, and every
// failure of the core thrown as an AnisomeshError carrying the core's code.

/** Error thrown by every anisomesh call that fails; `code` is stable (e.g. "INVALID_METRIC"). */
export class AnisomeshError extends Error {
  constructor(code, message) {
    super(message);
    this.name = 'AnisomeshError';
    this.code = code;
  }
}

function unwrap(result) {
  if (result && typeof result.error === 'string') throw new AnisomeshError(result.error, result.message);
  return result;
}

function argError(message) {
  return new AnisomeshError('INVALID_ARGUMENT', message);
}

function checkMetricSpec(spec, name) {
  if (spec === null || typeof spec !== 'object') {
    throw argError(`${name}: expected a metric object {alpha, h1, h2}, {h} or {m11, m12, m22}, got ${spec === null ? 'null' : typeof spec}`);
  }
  for (const key of ['alpha', 'h1', 'h2', 'h', 'm11', 'm12', 'm22']) {
    if (key in spec && typeof spec[key] !== 'number') {
      throw argError(`${name}.${key}: expected a number, got ${typeof spec[key]}`);
    }
  }
  return spec;
}

function checkVector(v, name) {
  if (!(Array.isArray(v) || ArrayBuffer.isView(v)) || v.length !== 2 || typeof v[0] !== 'number' || typeof v[1] !== 'number') {
    throw argError(`${name}: expected [x, y]`);
  }
  return v;
}

function metricOut(r) {
  const { m11, m12, m22, t11, t12, t22, alpha, h1, h2 } = r;
  return { m11, m12, m22, t11, t12, t22, alpha, h1, h2 };
}

/** Wraps an instantiated embind module into the public API object. */
export function wrapCore(core) {
  return Object.freeze({
    /** Version of the core. */
    version: core.version(),
    /** A metric from {alpha, h1, h2}, {h} or {m11, m12, m22}; returns all three forms. */
    metric(spec) {
      return metricOut(unwrap(core.metricCreate(checkMetricSpec(spec, 'metric'))));
    },
    /** Metric intersection: the largest unit ellipse inside both (the paper's min(M1, M2)). */
    intersectMetrics(a, b) {
      return metricOut(unwrap(core.metricIntersect(checkMetricSpec(a, 'a'), checkMetricSpec(b, 'b'))));
    },
    /** Interpolation of the transformation matrices: (1 - t) Mt_a + t Mt_b. */
    interpolateMetrics(a, b, t) {
      if (typeof t !== 'number') throw argError('t: expected a number in [0, 1]');
      return metricOut(unwrap(core.metricInterpolate(checkMetricSpec(a, 'a'), checkMetricSpec(b, 'b'), t)));
    },
    /** Metric length sqrt(v^T M v) of the vector v = [dx, dy]. */
    metricLength(m, v) {
      checkVector(v, 'v');
      return unwrap(core.metricLength(checkMetricSpec(m, 'metric'), v[0], v[1])).length;
    },
    /** diff(M1, M2): the largest relative change of requested length over all directions. */
    metricDifference(a, b) {
      return unwrap(core.metricDifference(checkMetricSpec(a, 'a'), checkMetricSpec(b, 'b'))).difference;
    },
    /** The unit ellipse of a metric around center, as a Float64Array of xy pairs. */
    metricEllipse(m, center = [0, 0], segments = 64) {
      checkVector(center, 'center');
      if (!Number.isInteger(segments)) throw argError('segments: expected an integer');
      return unwrap(core.metricEllipse(checkMetricSpec(m, 'metric'), center[0], center[1], segments)).points;
    },
  });
}

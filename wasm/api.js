// The JavaScript face of anisomesh, shared by the Node and browser entry points.
// It hides embind: plain objects in, plain objects and typed arrays out, and every
// failure of the core thrown as an AnisomeshError carrying the core's code.

// One class for the ESM entry points and the CommonJS one (wasm/index.cjs), whichever loads
// first: `instanceof AnisomeshError` holds across them.
const errorKey = Symbol.for('anisomesh.AnisomeshError');

/** Error thrown by every anisomesh call that fails; `code` is stable (e.g. "INVALID_METRIC"). */
export const AnisomeshError = (globalThis[errorKey] ??= class AnisomeshError extends Error {
  constructor(code, message) {
    super(message);
    this.name = 'AnisomeshError';
    this.code = code;
  }
});

function unwrap(result) {
  if (result && typeof result.error === 'string') throw new AnisomeshError(result.error, result.message);
  return result;
}

// The user's callbacks among options[keys], run from inside the core: an exception thrown
// by one must not unwind through the core's frames (their destructors would not run and the
// memory they hold would leak). It is caught here, the callback answers false (which cancels
// the run), and call() throws it once the core has returned.
function callbacksGuarded(options, keys, call) {
  let thrown = false, error;
  const wrapped = { ...options };
  for (const key of keys) {
    const f = options[key];
    if (typeof f !== 'function') continue;
    wrapped[key] = (...args) => {
      if (thrown) return false;
      try {
        return f(...args);
      } catch (e) {
        thrown = true;
        error = e;
        return false;
      }
    };
  }
  let result;
  try {
    result = call(wrapped);
  } catch (e) {
    if (thrown) throw error;
    throw e;
  }
  if (thrown) throw error;
  return result;
}

// The options meshCase takes (MeshCaseOptions in index.d.ts).
const MESH_CASE_OPTIONS = ['inspectControlSpace', 'vertexMetrics', 'measures', 'elementMeasures', 'stats', 'quads', 'allQuads',
  'maxElements', 'controlSpaceUpdates', 'controlSpaceGlyphs', 'patchParams', 'onProgress', 'svg', 'vtu'];

// The options remesh takes (RemeshOptions in index.d.ts).
const REMESH_OPTIONS = ['hmin', 'hmax', 'hgrad', 'hsiz', 'maxElements', 'onProgress', 'onStage', 'stats', 'svg', 'vtu'];

// As unknown fields of a case are refused, so are unknown options (a typo would be ignored).
function checkKnownOptions(options, known) {
  for (const key of Object.keys(options)) {
    if (!known.includes(key)) throw argError(`options.${key}: unknown option (known: ${known.join(', ')})`);
  }
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

function caseText(c, name = 'case') {
  if (typeof c === 'string') return c;
  if (c === null || typeof c !== 'object') throw argError(`${name}: expected a case object or JSON text`);
  // JSON.stringify would write NaN and Infinity as null (the core would then report a null
  // where the caller gave a number) and throws its own errors on cycles, BigInts and very
  // deep objects: each becomes an INVALID_ARGUMENT naming where it is.
  const path = [];
  const seen = new Set();
  const where = () => name + path.map((k) => (typeof k === 'number' ? `[${k}]` : `.${k}`)).join('');
  const check = (v, depth) => {
    if (typeof v === 'number' && !Number.isFinite(v)) throw argError(`${where()}: expected a finite number, got ${v}`);
    if (typeof v === 'bigint') throw argError(`${where()}: a BigInt cannot be written as JSON (use a number)`);
    if (v === null || typeof v !== 'object') return;
    if (depth > 256) throw argError(`${where()}: nested more than 256 levels deep`);
    if (seen.has(v)) throw argError(`${where()}: the case refers to itself (a cycle)`);
    if (typeof v.toJSON === 'function') return;
    seen.add(v);
    const keys = Array.isArray(v) ? v.keys() : Object.keys(v);
    for (const k of keys) {
      path.push(k);
      check(v[k], depth + 1);
      path.pop();
    }
    seen.delete(v);
  };
  check(c, 0);
  try {
    return JSON.stringify(c);
  } catch (e) {
    throw argError(`${name}: cannot be written as JSON: ${e.message}`);
  }
}

// A surface case (examples/SURFACE_FORMAT.md) has top-level "patches" (isSurfaceCaseJson in the core).
function isSurfaceCaseText(text) {
  try {
    const c = JSON.parse(text);
    return c !== null && typeof c === 'object' && !Array.isArray(c) && 'patches' in c;
  } catch {
    return false;  // the core reports the parse error
  }
}

const meshArrays = {
  vertices: Float64Array, params: Float64Array, triangles: Uint32Array, quads: Uint32Array, edges: Uint32Array,
  vertexRefs: Int32Array, triangleRefs: Int32Array, quadRefs: Int32Array, edgeRefs: Int32Array,
};
const arity = { triangles: 3, quads: 4, edges: 2 };

// Checks a mesh object's fields (types and shapes) before it crosses into the core.
function checkMesh(mesh, name = 'mesh') {
  if (mesh === null || typeof mesh !== 'object') throw argError(`${name}: expected a mesh object`);
  if (mesh.dimension !== 2 && mesh.dimension !== 3) throw argError(`${name}.dimension: expected 2 or 3`);
  if (!(mesh.vertices instanceof Float64Array)) throw argError(`${name}.vertices: expected a Float64Array`);
  if (mesh.vertices.length % mesh.dimension !== 0) {
    throw argError(`${name}.vertices: length ${mesh.vertices.length} is not a multiple of dimension ${mesh.dimension}`);
  }
  for (const [key, type] of Object.entries(meshArrays)) {
    if (key === 'vertices' || mesh[key] === undefined) continue;
    if (!(mesh[key] instanceof type)) throw argError(`${name}.${key}: expected a ${type.name}`);
    if (arity[key] && mesh[key].length % arity[key] !== 0) {
      throw argError(`${name}.${key}: length ${mesh[key].length} is not a multiple of ${arity[key]}`);
    }
  }
  return mesh;
}

function checkMetrics(metrics, vertexCount, name = 'metrics') {
  if (!(metrics instanceof Float64Array)) throw argError(`${name}: expected a Float64Array of m11, m12, m22 per vertex`);
  if (metrics.length !== 3 * vertexCount) {
    throw argError(`${name}: ${metrics.length / 3} tensors (length ${metrics.length}) for ${vertexCount} vertices`);
  }
  return metrics;
}

// Fields for metricFromField/adapt: a non-empty array of Float64Array, vertexCount values each.
function checkFieldValues(fields, vertexCount) {
  const list = fields instanceof Float64Array ? [fields] : fields;
  if (!Array.isArray(list) || list.length === 0) throw argError('fields: expected a non-empty array of Float64Array (or of expressions in x, y)');
  list.forEach((f, i) => {
    if (!(f instanceof Float64Array)) throw argError(`fields[${i}]: expected a Float64Array of one value per vertex`);
    if (f.length !== vertexCount) throw argError(`fields[${i}]: ${f.length} values for ${vertexCount} vertices`);
  });
  return list;
}

// Options of metricFromField/adapt, checked for type (ranges are the core's).
function checkAdaptOptions(options) {
  if (options === null || typeof options !== 'object') throw argError('options: expected an object');
  const out = {};
  for (const key of ['err', 'nv', 'hmin', 'hmax', 'anisomax', 'hgrad', 'maxElements', 'iterations']) {
    const v = options[key];
    if (v === undefined) continue;
    if (!(typeof v === 'number' && Number.isFinite(v) && v >= 0)) throw argError(`options.${key}: expected a finite nonnegative number`);
    out[key] = v;
  }
  // The core's bound (kMaxAdaptIterations): a larger count would wrap in the int it takes.
  if (out.iterations !== undefined && !(Number.isInteger(out.iterations) && out.iterations >= 1 && out.iterations <= 1000)) {
    throw argError('options.iterations: expected an integer in [1, 1000]');
  }
  if (options.relative !== undefined) out.relative = Boolean(options.relative);
  if (options.measures !== undefined) out.measures = Boolean(options.measures);
  if (options.norm !== undefined) {
    const n = String(options.norm);
    if (!['1', '2', 'inf'].includes(n)) throw argError(`options.norm: expected 1, 2 or 'inf', got ${options.norm}`);
    out.norm = n;
  }
  if (options.shape !== undefined) {
    if (!['anisotropic', 'isotropic', 'uniform'].includes(options.shape)) {
      throw argError("options.shape: expected 'anisotropic', 'isotropic' or 'uniform'");
    }
    out.shape = options.shape;
  }
  return out;
}

// options.svg: true or { uv, view: [azimuth, elevation] in degrees, controlSpace }, passed to
// the core as { uv, azimuth, elevation (radians), controlSpace }.
function checkSvgOption(svg) {
  if (svg === undefined || svg === false) return undefined;
  if (svg === true) return {};
  if (svg === null || typeof svg !== 'object') throw argError('options.svg: expected true or { uv?, view?, controlSpace? }');
  const out = {};
  for (const key of ['uv', 'controlSpace']) {
    if (svg[key] !== undefined && typeof svg[key] !== 'boolean') throw argError(`options.svg.${key}: expected a boolean`);
    if (svg[key]) out[key] = true;
  }
  if (svg.view !== undefined) {
    const v = svg.view;
    if (!Array.isArray(v) || v.length !== 2 || !v.every((x) => typeof x === 'number' && Number.isFinite(x))) {
      throw argError('options.svg.view: expected [azimuth, elevation] in degrees');
    }
    out.azimuth = v[0] * 0.017453292519943295;
    out.elevation = v[1] * 0.017453292519943295;
  }
  return out;
}

// Frees core handles (control spaces, kept runs) the user forgot to dispose(), once garbage collected.
const registry = typeof FinalizationRegistry === 'function' ? new FinalizationRegistry((handle) => handle.delete()) : null;

// The kept run of a meshCase made with { stats: false } (a handle of the core):
// report() makes its quality report once and frees it, dispose() frees it unreported;
// forgotten, it is freed when the result is garbage collected.
function deferredReport(handle, owner) {
  let live = handle;
  registry?.register(owner, handle, owner);
  const free = () => {
    if (!live) return;
    registry?.unregister(owner);
    live.delete();
    live = null;
  };
  return {
    report() {
      if (!live) throw new AnisomeshError('INVALID_ARGUMENT', 'report(): this run\'s report was already made or disposed');
      try {
        return JSON.parse(unwrap(live.stats()).stats);
      } finally {
        free();
      }
    },
    // Surface runs made with { elementMeasures: false }: the per-element quality and edge
    // lengths measures would have had, made now (the run stays kept for report()).
    elementMeasures() {
      if (!live) throw new AnisomeshError('INVALID_ARGUMENT', 'elementMeasures(): this run\'s report was already made or disposed');
      return unwrap(live.elementMeasures());
    },
    dispose: free,
  };
}

/** A control space being inspected or edited; free it with dispose(). */
class ControlSpace {
  #handle;
  /** The embind handle, for minimumControlSpace() (internal). */
  static handleOf(cs) {
    if (!(cs instanceof ControlSpace)) throw argError('expected a ControlSpace from createControlSpace() or minimumControlSpace()');
    return cs.#live();
  }
  constructor(handle) {
    this.#handle = handle;
    registry?.register(this, handle, this);
  }
  #live() {
    if (!this.#handle) throw new AnisomeshError('INVALID_ARGUMENT', 'control space used after dispose()');
    return this.#handle;
  }
  /** The metric at one point [x, y]. */
  metricAt(p) {
    checkVector(p, 'p');
    const m = unwrap(this.#live().metricsAt(new Float64Array(p))).metrics;
    return { m11: m[0], m12: m[1], m22: m[2] };
  }
  /** Metrics at many points (xy pairs): Float64Array of m11, m12, m22 per point. */
  metricsAt(xy) {
    if (!(xy instanceof Float64Array) || xy.length % 2 !== 0) throw argError('xy: expected a Float64Array of x, y pairs');
    return unwrap(this.#live().metricsAt(xy)).metrics;
  }
  /** Nodes with metrics and cells (quadtree leaves or triangles), for display. */
  inspect({ sampleGrid = 32 } = {}) {
    return JSON.parse(unwrap(this.#live().inspect(sampleGrid)).json);
  }
  /** Legacy VTK text of the structure with per-node metrics (ParaView). */
  toVtk() {
    return unwrap(this.#live().toVtk()).text;
  }
  /** Frees the core's memory; later calls throw. Safe to call twice. */
  dispose() {
    if (!this.#handle) return;
    registry?.unregister(this);
    this.#handle.delete();
    this.#handle = null;
  }
}

function metricOut(r) {
  const { m11, m12, m22, t11, t12, t22, alpha, h1, h2 } = r;
  return { m11, m12, m22, t11, t12, t22, alpha, h1, h2 };
}

// Large texts cross into the core as UTF-8 bytes from TextEncoder, copied with one
// TypedArray.set (bindings.cpp textOf); embind's string conversion is a JS loop.
const encoder = new TextEncoder();
const utf8 = (text) => (text.length > 1 << 16 ? encoder.encode(text) : text);

/** Wraps an instantiated embind module into the public API object. */
export function wrapCore(core) {
  return Object.freeze({
    /** Version of the core. */
    version: core.version(),
    /** Bytes malloc has in use in the wasm heap, and the heap's size (for leak checks). */
    memoryStats() {
      return core.memoryStats();
    },
    /** Threads of the parallel stages (1 in the single-threaded module); returns the count in effect. */
    setThreads(threads) {
      if (!Number.isInteger(threads) || threads < 1) throw argError('threads: expected a positive integer');
      // Above the core's int (which would wrap, e.g. 2^31 to a negative count): the most there is.
      return core.setThreads(Math.min(threads, 0x7fffffff));
    },
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
    /**
     * Meshes a JSON case, planar (examples/CASE_FORMAT.md) or surface (SURFACE_FORMAT.md),
     * given as an object or JSON text. Returns { mesh, stats, controlSpace } with typed
     * arrays in mesh. onProgress(fraction) is called while meshing; returning false
     * cancels the run (AnisomeshError CANCELLED).
     */
    meshCase(c, options = {}) {
      if (options === null || typeof options !== 'object') throw argError('options: expected an object');
      checkKnownOptions(options, MESH_CASE_OPTIONS);
      const { onProgress, maxElements } = options;
      if (onProgress !== undefined && typeof onProgress !== 'function') throw argError('options.onProgress: expected a function');
      if (maxElements !== undefined && !(Number.isInteger(maxElements) && maxElements > 0)) {
        throw argError('options.maxElements: expected a positive integer');
      }
      for (const key of ['inspectControlSpace', 'vertexMetrics', 'measures', 'elementMeasures', 'stats', 'quads', 'allQuads', 'controlSpaceUpdates', 'vtu', 'controlSpaceGlyphs', 'patchParams']) {
        if (options[key] !== undefined && typeof options[key] !== 'boolean') throw argError(`options.${key}: expected a boolean`);
      }
      const svg = checkSvgOption(options.svg);
      const text = caseText(c);
      const r = callbacksGuarded({ ...options, svg }, ['onProgress'], (o) => unwrap(core.meshCase(text, o)));
      const result = {
        mesh: r.mesh,
        ...(svg !== undefined ? { svg: r.svg } : {}),
        ...(options.vtu ? { vtu: r.vtu } : {}),
        stats: r.stats === null ? null : JSON.parse(r.stats),
        controlSpace: r.controlSpace ? JSON.parse(r.controlSpace) : null,
        vertexMetrics: r.vertexMetrics,
        measures: r.measures,
        timings: r.timings,
        // Surface cases only, when asked for: the final control spaces drawn as ellipses
        // ({ patch, offsets, uv, xyz }), each element's patch and its corners' (u, v) in it.
        ...(r.glyphs ? { glyphs: r.glyphs } : {}),
        ...(r.elementPatch ? { elementPatch: r.elementPatch, cornerParams: r.cornerParams } : {}),
      };
      if (r.report) Object.assign(result, deferredReport(r.report, result));
      return result;
    },
    /** Remeshes the domain bounded by mesh's boundary edges under per-vertex tensors (m11, m12, m22). */
    remesh(mesh, metrics, options = {}) {
      checkMesh(mesh);
      if (metrics !== null) checkMetrics(metrics, mesh.vertices.length / mesh.dimension);
      if (options === null || typeof options !== 'object') throw argError('options: expected an object');
      checkKnownOptions(options, REMESH_OPTIONS);
      for (const key of ['hmin', 'hmax', 'hgrad', 'hsiz']) {
        const v = options[key];
        if (v !== undefined && !(typeof v === 'number' && Number.isFinite(v) && v >= 0)) {
          throw argError(`options.${key}: expected a finite nonnegative number`);
        }
      }
      if (options.maxElements !== undefined && !(Number.isInteger(options.maxElements) && options.maxElements > 0)) {
        throw argError('options.maxElements: expected a positive integer');
      }
      for (const key of ['onProgress', 'onStage']) {
        if (options[key] !== undefined && typeof options[key] !== 'function') throw argError(`options.${key}: expected a function`);
      }
      if (options.stats !== undefined && typeof options.stats !== 'boolean') throw argError('options.stats: expected a boolean');
      const svg = checkSvgOption(options.svg);
      const r = callbacksGuarded({ ...options, svg }, ['onProgress', 'onStage'], (o) => unwrap(core.remesh(mesh, metrics, o)));
      const result = {
        mesh: r.mesh,
        stats: r.stats === null ? null : JSON.parse(r.stats),
        ...(svg !== undefined ? { svg: r.svg } : {}),
        ...(options.vtu ? { vtu: r.vtu } : {}),
      };
      // stats: false: the quality report on demand (report()), as meshCase.
      if (r.report) Object.assign(result, deferredReport(r.report, result));
      return result;
    },
    /**
     * The metric of one or several fields (Float64Array of one value per vertex each) on a
     * planar mesh: Hessian recovery, then error level (err) or target vertex count (nv).
     */
    metricFromField(mesh, fields, options = {}) {
      checkMesh(mesh);
      const values = checkFieldValues(fields, mesh.vertices.length / mesh.dimension);
      return unwrap(core.metricFromField(mesh, values, checkAdaptOptions(options)));
    },
    /**
     * Adapts a planar mesh to fields: per-vertex values (Float64Array, transferred between
     * iterations) or expressions in x, y (strings, re-sampled on every mesh).
     */
    adapt(mesh, fields, options = {}) {
      checkMesh(mesh);
      const list = Array.isArray(fields) ? fields : [fields];
      const expressions = list.every((f) => typeof f === 'string') ? list : [];
      const values = expressions.length ? [] : checkFieldValues(list, mesh.vertices.length / mesh.dimension);
      return unwrap(core.adapt(mesh, values, expressions, checkAdaptOptions(options)));
    },
    /** The mesh as text: 'mesh' (Medit), 'vtk', 'obj', 'msh', 'msh2' or 'svg'; 'meshb': bytes (a Uint8Array). */
    writeMesh(mesh, format = 'mesh') {
      checkMesh(mesh);
      const out = unwrap(core.writeMesh(mesh, String(format)));
      return out.bytes ?? out.text;
    },
    /**
     * Parses mesh text ('mesh', 'vtk', 'obj', 'msh'), as a string or as its UTF-8 bytes (a
     * Uint8Array, e.g. a file read without decoding: no string round trip), or the bytes of
     * a 'meshb'.
     */
    readMesh(text, format = 'mesh') {
      if (String(format) === 'meshb') {
        if (!(text instanceof Uint8Array)) throw argError('bytes: expected a Uint8Array for the meshb format');
      } else if (typeof text !== 'string' && !(text instanceof Uint8Array)) {
        throw argError('text: expected a string or its UTF-8 bytes (a Uint8Array)');
      }
      return unwrap(core.readMesh(typeof text === 'string' ? utf8(text) : text, String(format))).mesh;
    },
    /**
     * Parses a Medit .sol (scalar sizes or tensors; a string or its UTF-8 bytes) for
     * vertexCount vertices: Float64Array m11, m12, m22 per vertex.
     */
    readSol(text, vertexCount) {
      if (typeof text !== 'string' && !(text instanceof Uint8Array)) {
        throw argError('text: expected a string or its UTF-8 bytes (a Uint8Array)');
      }
      if (!Number.isInteger(vertexCount) || vertexCount < 0) throw argError('vertexCount: expected a non-negative integer');
      return unwrap(core.readSol(typeof text === 'string' ? utf8(text) : text, vertexCount)).metrics;
    },
    /** Writes per-vertex tensors (m11, m12, m22) as a Medit .sol. */
    writeSol(metrics) {
      if (!(metrics instanceof Float64Array) || metrics.length % 3 !== 0) throw argError('metrics: expected a Float64Array of m11, m12, m22 per vertex');
      return unwrap(core.writeSol(metrics)).text;
    },
    /**
     * Parses an expression in two variables (u, v, or the names in options.variables, e.g.
     * ['x', 'y'] for planar size fields); returns its value there or throws PARSE_ERROR with the column.
     */
    evaluateExpression(text, u = 0, v = 0, { variables = ['u', 'v'] } = {}) {
      if (typeof text !== 'string') throw argError('text: expected a string');
      if (!Array.isArray(variables) || variables.length !== 2 || !variables.every((n) => typeof n === 'string')) {
        throw argError('options.variables: expected two names, e.g. ["x", "y"]');
      }
      return unwrap(core.checkExpression(text, u, v, variables[0], variables[1])).value;
    },
    /**
     * A planar case's "domain" ({ outer, holes }, examples/CASE_FORMAT.md) from an SVG
     * drawing: its closed paths, polygons, rects, circles and ellipses (lines, arcs,
     * quadratic and cubic Beziers), the one outermost shape the outer contour and the shapes
     * inside it holes, scaled so the larger side is options.size (y flipped to stay upright
     * unless options.flipY is false).
     */
    domainFromSvg(text, options = {}) {
      if (typeof text !== 'string') throw argError('text: expected the SVG document as a string');
      if (options === null || typeof options !== 'object') throw argError('options: expected an object');
      const { size = 1, flipY = true } = options;
      if (typeof size !== 'number' || !(size > 0) || !Number.isFinite(size)) throw argError('options.size: expected a positive number');
      if (typeof flipY !== 'boolean') throw argError('options.flipY: expected a boolean');
      return JSON.parse(unwrap(core.domainFromSvg(text, size, flipY)).json);
    },
    /**
     * Builds the control space of a case (its controlSpace, sources and domain); for a
     * surface case (with "patches") the initial control space of one patch in its (u, v)
     * plane (options.patch, default 0). Call dispose() when done.
     */
    createControlSpace(c, options = {}) {
      if (options === null || typeof options !== 'object') throw argError('options: expected an object');
      const { patch = 0 } = options;
      if (!Number.isInteger(patch) || patch < 0) throw argError('options.patch: expected a non-negative integer');
      const text = caseText(c);
      const handle = new core.ControlSpaceHandle();
      try {
        unwrap(isSurfaceCaseText(text) ? handle.buildPatch(text, patch) : handle.build(text));
      } catch (e) {
        handle.delete();
        throw e;
      }
      return new ControlSpace(handle);
    },
    /** The exact minimum (intersection) of two or more control spaces, evaluated per query. */
    minimumControlSpace(...spaces) {
      if (spaces.length < 2) throw argError('minimumControlSpace: expected at least two control spaces');
      let acc = null;
      try {
        for (let i = 1; i < spaces.length; ++i) {
          const handle = new core.ControlSpaceHandle();
          try {
            const first = acc ? ControlSpace.handleOf(acc) : ControlSpace.handleOf(spaces[0]);
            unwrap(handle.buildMinimum(first, ControlSpace.handleOf(spaces[i])));
          } catch (e) {
            handle.delete();
            throw e;
          }
          acc?.dispose();  // the new minimum shares what it needs
          acc = new ControlSpace(handle);
        }
      } catch (e) {
        acc?.dispose();
        throw e;
      }
      return acc;
    },
  });
}

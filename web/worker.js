// Web Worker: all anisomesh work runs here so the page never freezes.
//
// Protocol (see jobs.js):
//   in : { type: 'init', module?: WebAssembly.Module, cancelFlag?: Int32Array, threads?: number }  once, right after start
//        { type: 'job', id, op, args, postedAt }
//   out: { type: 'ready', version, initMs, threads? }
//        { type: 'progress', id, stage, fraction }             during a job (fraction in [0, 1] or null)
//        { type: 'result', id, ok: true, result, workerMs, marks } | { type: 'result', id, ok: false, error }
// Typed arrays in results are transferred, not copied. marks: wall-clock times
// (performance.timeOrigin + now, comparable with the page's) of the job's steps.
//
// The core is synchronous, so a job is interrupted from inside only through its progress
// callback: on a cross-origin isolated page the page raises cancelFlag (shared memory) and
// the mesh job's callback tells the core to stop; elsewhere the page cancels a stale job by
// terminating this worker and starting a fresh one (cheap because the page compiles the
// wasm once and posts the compiled WebAssembly.Module here).
import createAnisomeshCore from '../wasm/dist/anisomesh-core.js';
import { wrapCore } from '../wasm/api.js';

let am = null;
// Int32Array on a SharedArrayBuffer from the page (cross-origin isolated pages only): the
// jobs with ids below its value are cancelled (see jobs.js).
let cancelFlag = null;
const cancelled = (id) => cancelFlag !== null && id < Atomics.load(cancelFlag, 0);
let readyResolve;
const ready = new Promise((r) => { readyResolve = r; });
const queue = [];

async function init(module, threads) {
  const t0 = performance.now();
  if (threads > 1) {
    // The pthreads build (the page is cross-origin isolated): fetched and compiled here.
    const { loadAnisomesh } = await import('../wasm/threads.js');
    am = await loadAnisomesh({ threads });  // a pool of threads - 1 workers, not one per core
    const inEffect = am.setThreads(threads);
    readyResolve();
    self.postMessage({ type: 'ready', version: am.version, initMs: performance.now() - t0, threads: inEffect });
    return;
  }
  const options = module
    ? {
      // Emscripten hook: instantiate the precompiled module instead of fetching + compiling again.
      instantiateWasm(imports, receiveInstance) {
        WebAssembly.instantiate(module, imports).then((instance) => receiveInstance(instance, module));
        return {};
      },
    }
    : { locateFile: () => new URL('../wasm/dist/anisomesh-core.wasm', import.meta.url).href };
  am = wrapCore(await createAnisomeshCore(options));
  readyResolve();
  self.postMessage({ type: 'ready', version: am.version, initMs: performance.now() - t0 });
}

// The control space inspection as compact typed arrays for the overlay:
// nodes: x, y, h1, h2, alpha per node; lines: x0, y0, x1, y1 per segment.
function overlayFromInspect(cs) {
  if (!cs) return null;
  const src = cs.nodes ?? cs.samples ?? [];
  const nodes = new Float32Array(5 * src.length);
  src.forEach((n, i) => nodes.set([n.p[0], n.p[1], n.h1, n.h2, n.alpha], 5 * i));
  const lines = [];
  if (cs.boxes) {  // quadtree leaves
    for (const [x0, y0, x1, y1] of cs.boxes) lines.push(x0, y0, x1, y0, x1, y0, x1, y1, x1, y1, x0, y1, x0, y1, x0, y0);
  } else if (cs.cells && cs.nodes) {  // background triangles (or leaves as node loops)
    for (const cell of cs.cells) {
      for (let j = 0; j < cell.length; j++) {
        const p = cs.nodes[cell[j]].p, q = cs.nodes[cell[(j + 1) % cell.length]].p;
        lines.push(p[0], p[1], q[0], q[1]);
      }
    }
  }
  // A sampled analytic field has no structure of its own: only the ellipses are drawn.
  const kind = cs.kind ?? (cs.samples ? 'sampled' : 'adaptive');
  return { kind, sampled: Boolean(cs.samples), nodes, lines: Float32Array.from(lines), bounds: cs.bounds ?? null };
}

// A surface run's final control spaces for the overlay: the core's ellipses per patch,
// in (u, v) for the 2D view and mapped onto the surface for the 3D view.
function overlayFromGlyphs(g) {
  if (!g) return null;
  return { kind: 'glyphs', sampled: false, glyphs: { patch: g.patch, offsets: g.offsets, uv: Float32Array.from(g.uv), xyz: g.xyz } };
}

// Legacy VTK of a sampled control space (analytic fields have no structure of their own
// to export with toVtk): the sample points as a structured grid with the metric tensors.
function sampledVtk(cs) {
  const n = cs.samples.length;
  const out = ['# vtk DataFile Version 3.0', 'anisomesh control space (sampled)', 'ASCII', 'DATASET STRUCTURED_GRID',
    `DIMENSIONS ${cs.nx} ${cs.ny} 1`, `POINTS ${n} double`];
  for (const s of cs.samples) out.push(`${s.p[0]} ${s.p[1]} 0`);
  out.push(`POINT_DATA ${n}`, 'TENSORS metric double');
  for (const s of cs.samples) out.push(`${s.m[0]} ${s.m[1]} 0`, `${s.m[1]} ${s.m[2]} 0`, '0 0 0');
  for (const key of ['h1', 'h2', 'alpha']) {
    out.push(`SCALARS ${key} double 1`, 'LOOKUP_TABLE default');
    for (const s of cs.samples) out.push(String(s[key]));
  }
  return out.join('\n') + '\n';
}

const wallNow = () => performance.timeOrigin + performance.now();
let lastMeshJob = null;  // id of the mesh job whose run the core keeps for its report
let keptRun = null;  // that job's meshCase result, whose report() makes the report
let keptWithoutElements = false;  // a surface run made while dragging: its colours come with the report

// The planar mesher reports a fraction: 0 while the control space and its section 3.2
// rounds run, then boundary (to 0.1), point insertion (to 0.8), improvement (to 0.95).
function stageOf(fraction) {
  if (fraction <= 0) return 'control space';
  if (fraction < 0.1) return 'boundary';
  if (fraction < 0.8) return 'inserting points';
  if (fraction < 1) return 'improving';
  return 'finishing';
}

const ops = {
  // Meshes a case (planar or surface: meshCase takes both): the mesh with per-edge metric
  // lengths and per-element qualities for the colouring (measured in the core). The
  // quality report is a separate job ('report'), which the page asks for once the mesh is
  // drawn, and skips for the meshes a drag has already left behind (a surface run's 3D
  // measures, chord deviations and the rest, are made there too).
  // overlay: also inspect the final control space for the overlay (planar only).
  // dragging (surfaces): leave the per-element 3D quality and edge lengths (the colours) to
  // the report too; the mesh comes sooner and is drawn plain until the report is in.
  // progress: false posts no progress messages (a drag's jobs; the core still polls for cancellation).
  mesh({ case: c, surface = false, overlay = false, dragging = false, progress: withProgress = true }, { progress: post, marks, id }) {
    const progress = withProgress ? post : () => {};
    progress('control space', 0);
    let lastFraction = -1, lastAt = 0;
    const onProgress = (fraction) => {
      const now = performance.now();
      // A message per stage change or per 2 % (at most every 30 ms): the page shows it.
      if (stageOf(fraction) !== stageOf(lastFraction) || (fraction - lastFraction >= 0.02 && now - lastAt >= 30)) {
        lastFraction = fraction;
        lastAt = now;
        progress(stageOf(fraction), fraction);
      }
      return !cancelled(id);  // false: the core stops with CANCELLED
    };
    marks.coreStart = wallNow();
    const run = am.meshCase(c, {
      inspectControlSpace: overlay && !surface, controlSpaceGlyphs: overlay && surface, patchParams: surface,
      measures: true, elementMeasures: !(surface && dragging), stats: false, onProgress,
    });
    marks.coreEnd = wallNow();
    const { mesh, measures, timings } = run;
    keptRun?.dispose();  // the previous run's report was not asked for
    keptRun = run;
    keptWithoutElements = surface && dragging;
    lastMeshJob = id;
    return {
      mesh,
      // Surfaces: each element's patch and its corners' (u, v) in it (the 2D view lays the patches side by side).
      patches: surface ? { element: run.elementPatch, corners: run.cornerParams } : null,
      overlay: overlay ? (surface ? overlayFromGlyphs(run.glyphs) : overlayFromInspect(run.controlSpace)) : null,
      measures: { edges: measures.edges, edgeLength: measures.edgeLength ?? null, quality: measures.quality ?? null, vertexH: measures.vertexH ?? null },
      stats: run.stats,  // null: see 'report'
      core: timings,
    };
  },
  // Meshes a surface case as a drag does and drops the result: the core keeps each patch's
  // curvature stage (native/src/surface/curvature_stage_cache.h) and the instance's memory
  // has grown to the size of such a run, so this worker, a spare until a cancellation swaps
  // it in, meshes the case without evaluating the surface's curvature or growing its memory
  // again (a first run in a fresh instance took twice a warm one's time). Posted by
  // JobRunner.warmSpare().
  warm({ case: c }) {
    am.meshCase(c, { patchParams: true, measures: true, elementMeasures: false, stats: false }).dispose();
    return null;
  },
  // One iteration of the adaptation loop (the page runs them one at a time and draws each):
  // the mesh adapted to the expression u(x, y), the field at its vertices, the iteration's
  // figures (N, errors) and the mesh measured in the adaptation metric.
  adapt({ mesh, expression, options }, { progress, marks }) {
    progress('adapting', null);
    marks.coreStart = wallNow();
    const r = am.adapt(mesh, expression, { ...options, iterations: 1, measures: true });
    marks.coreEnd = wallNow();
    keptRun?.dispose();
    keptRun = null;
    lastMeshJob = null;
    return { mesh: r.mesh, field: r.fields[0], iteration: r.iterations[0], measures: r.measures };
  },
  // The quality report of the mesh job `of`, which must be the last job run here.
  report({ of }, { progress }) {
    if (of !== lastMeshJob) throw Object.assign(new Error(`report: job ${of} is not the last mesh job (${lastMeshJob})`), { code: 'INVALID_ARGUMENT' });
    progress('quality report', null);
    const t0 = performance.now();
    // A surface mesh made while dragging: its per-element measures (the colours) first.
    const measures = keptWithoutElements ? keptRun.elementMeasures() : null;
    const stats = keptRun.report();
    keptRun = null;
    lastMeshJob = null;
    return { stats, measures, reportMs: performance.now() - t0 };
  },
  // Text of the mesh in a file format.
  writeMesh({ mesh, format }) {
    return am.writeMesh(mesh, format);
  },
  // The control space as VTK (toVtk for adaptive structures, a sampled grid otherwise) or JSON.
  // A surface case: one control space per patch (the initial one of section 3.1, in its
  // (u, v) plane): JSON { patches: [...] }, VTK a list of texts (one file per patch).
  exportControlSpace({ case: c, format }) {
    const one = (patch) => {
      const cs = am.createControlSpace(c, { patch });
      try {
        const json = cs.inspect({ sampleGrid: 64 });
        if (format === 'json') return json;
        return json.samples ? sampledVtk(json) : cs.toVtk();
      } finally {
        cs.dispose();
      }
    };
    if (Array.isArray(c?.patches)) {
      const all = c.patches.map((_, p) => one(p));
      return format === 'json' ? JSON.stringify({ patches: all }, null, 1) : all;
    }
    const r = one(0);
    return format === 'json' ? JSON.stringify(r, null, 1) : r;
  },
  // Value of an expression at (u, v) or a PARSE_ERROR naming the column.
  checkExpression({ text, u = 0, v = 0 }) {
    return am.evaluateExpression(text, u, v, { variables: ['x', 'y'] });
  },
  // A planar domain from an SVG drawing (the core's parser), scaled to size.
  domainFromSvg({ text, size }) {
    return am.domainFromSvg(text, { size });
  },
  readMesh({ text, format }) {
    return am.readMesh(text, format);
  },
};

function transferables(value, out = []) {
  if (ArrayBuffer.isView(value)) out.push(value.buffer);
  else if (value && typeof value === 'object') for (const v of Object.values(value)) transferables(v, out);
  return out;
}

async function runJob({ id, op, args, postedAt }) {
  const marks = { posted: postedAt, received: wallNow() };
  await ready;
  marks.ready = wallNow();
  const t0 = performance.now();
  try {
    if (!(op in ops)) throw Object.assign(new Error(`unknown operation '${op}'`), { code: 'INVALID_ARGUMENT' });
    if (cancelled(id)) throw Object.assign(new Error('superseded by a newer job'), { code: 'CANCELLED' });
    const hooks = {
      id,
      marks,
      progress: (stage, fraction = null) => self.postMessage({ type: 'progress', id, stage, fraction }),
    };
    const result = ops[op](args ?? {}, hooks);
    marks.resultPosted = wallNow();
    const buffers = [...new Set(transferables(result))];
    self.postMessage({ type: 'result', id, ok: true, result, marks, workerMs: performance.now() - t0 }, buffers);
  } catch (e) {
    self.postMessage({ type: 'result', id, ok: false, error: { code: e.code ?? 'INTERNAL', message: e.message } });
  }
}

self.onmessage = ({ data }) => {
  if (data.type === 'init') {
    cancelFlag = data.cancelFlag ?? null;
    init(data.module, data.threads ?? 1).catch((e) => self.postMessage({ type: 'fatal', message: e.message }));
  } else if (data.type === 'job') {
    queue.push(data);
    // Jobs run one at a time in arrival order.
    if (queue.length === 1) drain();
  }
};

async function drain() {
  while (queue.length) {
    await runJob(queue[0]);
    queue.shift();
  }
}

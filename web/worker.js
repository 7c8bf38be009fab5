// Web Worker: all anisomesh work runs here so the page never freezes.
//
// Protocol (see jobs.js):
//   in : { type: 'init', module?: WebAssembly.Module }         once, right after start
//        { type: 'job', id, op, args }
//   out: { type: 'ready', version, initMs }
//        { type: 'progress', id, stage }                       between the steps of a job
//        { type: 'result', id, ok: true, result, workerMs } | { type: 'result', id, ok: false, error }
//
// The core is synchronous, so a job cannot be interrupted from inside: the page cancels
// a stale job by terminating this worker and starting a fresh one (cheap because the
// page compiles the wasm once and posts the compiled WebAssembly.Module here).
import createAnisomeshCore from '../wasm/dist/anisomesh-core.js';
import { wrapCore } from '../wasm/api.js';
import { measure, mtFromTensors, smallestSizes, uniqueEdges } from './measure.js';

let am = null;
let readyResolve;
const ready = new Promise((r) => { readyResolve = r; });
const queue = [];

async function init(module) {
  const t0 = performance.now();
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

// meshCase takes planar and surface cases alike (a surface case has "patches"); only
// planar runs export their control space.
function runCase(c, surface) {
  return am.meshCase(c, { inspectControlSpace: !surface, vertexMetrics: !surface });
}

const ops = {
  // Meshes a case; adds per-edge metric lengths and per-element qualities for the colouring.
  mesh({ case: c, surface = false }, progress) {
    progress('meshing');
    const t0 = performance.now();
    const { mesh, stats, controlSpace, vertexMetrics } = runCase(c, surface);
    const meshMs = performance.now() - t0;
    progress('measuring');
    let measures;
    if (!surface) {
      // The final control space's metric at the vertices (after the section 3.2 updates),
      // so the colours measure exactly what the report measures.
      measures = measure(mesh, mtFromTensors(vertexMetrics));
      measures.vertexH = smallestSizes(vertexMetrics);
    } else {
      // Surface metrics live on the surface: colours wait for the core to report them.
      measures = { edges: uniqueEdges(mesh.triangles, mesh.quads), edgeLength: null, quality: null, vertexH: null };
    }
    return { mesh, stats, overlay: overlayFromInspect(controlSpace), measures, meshMs };
  },
  // Text of the mesh in a file format.
  writeMesh({ mesh, format }) {
    return am.writeMesh(mesh, format);
  },
  // The control space as VTK (toVtk for adaptive structures, a sampled grid otherwise) or JSON.
  exportControlSpace({ case: c, format }) {
    const cs = am.createControlSpace(c);
    try {
      const json = cs.inspect({ sampleGrid: 64 });
      if (format === 'json') return JSON.stringify(json, null, 1);
      return json.samples ? sampledVtk(json) : cs.toVtk();
    } finally {
      cs.dispose();
    }
  },
  // Value of an expression at (u, v) or a PARSE_ERROR naming the column.
  checkExpression({ text, u = 0, v = 0 }) {
    return am.evaluateExpression(text, u, v, { variables: ['x', 'y'] });
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

async function runJob({ id, op, args }) {
  await ready;
  const t0 = performance.now();
  try {
    if (!(op in ops)) throw Object.assign(new Error(`unknown operation '${op}'`), { code: 'INVALID_ARGUMENT' });
    const result = ops[op](args ?? {}, (stage) => self.postMessage({ type: 'progress', id, stage }));
    const buffers = [...new Set(transferables(result))];
    self.postMessage({ type: 'result', id, ok: true, result, workerMs: performance.now() - t0 }, buffers);
  } catch (e) {
    self.postMessage({ type: 'result', id, ok: false, error: { code: e.code ?? 'INTERNAL', message: e.message } });
  }
}

self.onmessage = ({ data }) => {
  if (data.type === 'init') {
    init(data.module).catch((e) => self.postMessage({ type: 'fatal', message: e.message }));
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

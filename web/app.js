// The anisomesh browser app: presets, metric sources edited on the canvas and in the
// panel, live remeshing in a worker, quality numbers and histograms, export/import and
// the state in the URL.
import GUI from 'lil-gui';
import { JobRunner, CancelledError, wallNow } from './jobs.js';
import { presets, presetById, defaultPresetId } from './presets.js';
import { defaultView, encodeState, decodeState, checkCase, errorTarget, InputError } from './state.js';
import { Views, softwareWebGL } from './views.js';
import { moveHandle } from './overlays.js';
import { drawHistogram } from './histogram.js';
import { qualityColor, lengthColor, sizeColor, fieldColor, css } from './colors.js';
import { uniqueEdges } from './measure.js';
import { createSurfaceEditor } from './surface_editor.js';
import { createAdaptMode } from './adapt_mode.js';

const $ = (id) => document.getElementById(id);
const EDIT_DEBOUNCE_MS = 120;
const PROGRESS_LOG = 400;      // progress events kept for the test hook

// --- state ------------------------------------------------------------------------------

const state = {
  ready: false,
  presetId: null,
  case: null,
  view: defaultView(),
  selected: -1,
  caseVersion: 0,       // bumped on every edit; a result older than the current version is stale
  meshedVersion: -1,
  jobsStarted: 0,
  jobsDone: 0,
  jobsFailed: 0,
  cancelled: 0,
  laneJobs: 0,          // mesh jobs the second lane ran (inputs that did not wait for a stale job)
  staleResults: 0,      // results older than the mesh already drawn (the other lane's was newer)
  drawnVersions: [],    // case versions of the last 50 meshes drawn, in drawing order
  meshesDrawn: 0,       // meshes drawn since the page opened
  recolours: 0,         // meshes recoloured in place once their report came in (a surface drag)
  lastStats: null,
  lastError: null,      // { code, message, target }
  lastJob: null,        // { meshMs, workerMs, totalMs, drawMs }
  dragToMeshMs: null,   // pointer up -> new mesh drawn
  dragInputToMeshMs: null,  // the drag's last edit of the case -> its mesh drawn
  lastBreakdown: null,  // where the time of the last job went (see breakdown())
  breakdowns: [],       // the last 50 of them
  progressLog: [],      // { id, stage, fraction, at } of recent jobs (test hook)
  progress: null,       // { stage, fraction } of the running job
  syncDraw: false,      // measurements: renderMs waits for the GPU (a 1-pixel read back)
  workerStartMs: null,  // worker creation -> core ready (precompiled module)
  workerRestartMs: [],  // the same for replacement workers after a cancellation
  version: null,
  surface: false,
};

// --- workers ----------------------------------------------------------------------------

const status = $('status'), statusText = $('status-text'), spinner = status.querySelector('.spinner');
const progressBar = $('progress'), progressFill = progressBar.querySelector('.fill');
let progress = { stage: 'meshing', fraction: null, started: 0 };
let busy = false, busyTimer = null, spinStep = 0;
// While a handle is dragged the toolbar stands still (no busy state, stage or elapsed time):
// the mesh following the pointer shows the work, and on a software rasterizer every frame
// of the page costs the GPU process CPU on the cores the mesh workers use.
let toolbarQuiet = false, quietTimer = null;
const RELEASE_QUIET_MS = 300;  // after the release, a job still running by then shows again
// The toolbar while a job runs: the stage, its progress (a bar and a percentage when the
// core reports a fraction) and the elapsed time.
function showProgress() {
  if (toolbarQuiet) return;
  const pct = progress.fraction > 0 ? ` ${Math.round(100 * progress.fraction)} %` : '';
  statusText.textContent = `${progress.stage}${pct} · ${((performance.now() - progress.started) / 1000).toFixed(1)} s`;
  progressBar.hidden = progress.fraction == null;
  progressFill.style.width = `${(100 * (progress.fraction ?? 0)).toFixed(1)}%`;
  progressBar.setAttribute('aria-valuenow', String(Math.round(100 * (progress.fraction ?? 0))));
  // The spinner turns an eighth per update (100 ms) with the text, not as a CSS animation:
  // that one makes a frame per display refresh (60 a second) for as long as a job runs.
  spinner.style.transform = `rotate(${(spinStep = (spinStep + 1) % 8) * 45}deg)`;
}
// Shows the busy state (spinner, progress, a 100 ms update of the elapsed time) or hides it;
// the DOM is written only when that changes.
let busyShown = false;
function paintBusy() {
  const shown = busy && !toolbarQuiet;
  clearInterval(busyTimer);
  busyTimer = null;
  if (shown !== busyShown) {
    busyShown = shown;
    spinner.hidden = !shown;
    status.classList.toggle('busy', shown);
    if (!shown) progressBar.hidden = true;
  }
  if (shown) {
    showProgress();
    busyTimer = setInterval(showProgress, 100);
  }
}
function setBusy(b) {
  busy = b;
  if (b) progress = { stage: 'starting', fraction: null, started: performance.now() };
  else state.progress = null;
  paintBusy();
}
// Quiets the toolbar (a handle is dragged) or lets it show the running job again.
function quietToolbar(on) {
  clearTimeout(quietTimer);
  quietTimer = null;
  if (toolbarQuiet === on) return;
  toolbarQuiet = on;
  paintBusy();
}
const meshRunner = new JobRunner({
  supersede: true,
  precompiled: new URLSearchParams(location.search).get('precompile') !== '0',  // ?precompile=0 to measure the difference
  spare: new URLSearchParams(location.search).get('spare') !== '0',            // ?spare=0: no spare worker (for comparison)
  onBusy: setBusy,
  onProgress: ({ id, stage, fraction }) => {
    progress.stage = stage;
    // A stage without a fraction of its own (the quality report) keeps the bar where it was.
    if (fraction != null) progress.fraction = fraction;
    state.progress = { stage, fraction };
    state.progressLog.push({ id, stage, fraction, at: Math.round(performance.now()) });
    if (state.progressLog.length > PROGRESS_LOG) state.progressLog.splice(0, state.progressLog.length - PROGRESS_LOG);
    showProgress();
  },
});
const utilRunner = new JobRunner();  // exports and checks: never cancelled by meshing
// A second mesh lane for drags, on cross-origin isolated pages (cooperative cancellation):
// while one worker finishes the job of an input the pointer has since left (so the mesh
// follows the drag), the latest input starts at once in the other instead of waiting for
// it, and a newer input supersedes only that latest job. Made after the first mesh is
// drawn (warmLanes); ?lanes=1: a single lane (for comparison).
let laneRunner = null;
const laneCount = Number(new URLSearchParams(location.search).get('lanes') ?? 2);

// --- views ------------------------------------------------------------------------------

// The metric sources being edited: the planar case's, or those of the surface patch shown
// in the "Surface" folder (in its (u, v) plane). create: make the array when missing.
function sourceList({ create = false } = {}) {
  const c = state.case;
  if (!c) return [];
  const owner = state.surface ? c.patches?.[surfaceEditor.patch] : c;
  if (!owner) return [];
  if (create) owner.sources ??= [];
  return owner.sources ?? [];
}

let dragFrom = null;
const query = new URLSearchParams(location.search);
const views = new Views($('view'), {
  onSelect(i) { selectSource(i); },
  onDrag(i, key, p, phase) {
    const s = sourceList()[i];
    if (!s) return;
    if (phase === 'start') {
      dragFrom = { p, p1: s.p1 && [...s.p1], p2: s.p2 && [...s.p2] };
      views.dragging = true;  // the other view waits for the release (see draw())
      quietToolbar(true);
      return;
    }
    const before = JSON.stringify(s);
    moveHandle(s, key, p, dragFrom);
    const changed = JSON.stringify(s) !== before;
    views.setSources(sourceList(), state.selected, state.view.sources);
    sourceGui.controllersRecursive().forEach((c) => c.updateDisplay());
    if (phase === 'move') {
      if (changed) editedByDrag();
      return;
    }
    state.dragEndAt = wallNow();
    if (changed) bumpVersion();
    recordHistory();
    state.dragEndVersion = state.caseVersion;
    state.dragLastEditAt = state.editAt;
    // Released: the latest input must not wait behind a stale job. A job already running
    // for this very input goes on; a job for an older input is superseded at once.
    dragWaiting = false;
    clearTimeout(restTimer);
    views.dragging = false;
    // The toolbar stays quiet until the release's mesh is drawn, or shows a job still running after RELEASE_QUIET_MS.
    quietTimer = setTimeout(() => quietToolbar(false), RELEASE_QUIET_MS);
    if (state.meshedVersion === state.caseVersion) {
      // The mesh of the last input was drawn before the release.
      quietToolbar(false);
      state.dragToMeshMs = 0;
      const b = state.breakdowns.findLast((x) => x.version === state.caseVersion);
      state.dragInputToMeshMs = b ? Math.round(b.inputToDrawnMs) : 0;
      if (b) b.drag = true;
      if (b && !state.lastError) statusText.textContent = `meshed in ${(b.inputToDrawnMs / 1000).toFixed(2)} s`;
      state.dragEndAt = null;
      views.requestRender('all');
    } else if (!cancelStaleLanes()) {
      clearTimeout(editTimer);
      editTimer = null;
      remesh(runnerForLatest());
      cancelStaleLanes();
    }
  },
  // A click on the surface (3D) or in (u, v) with a source armed by "+ radial / segment source".
  onPlace(hit) { placeSource(hit); },
}, {
  // ?aa=1 / ?aa=0 forces antialiasing; by default it is off on software WebGL (4x slower there).
  antialias: query.has('aa') ? query.get('aa') !== '0' : !softwareWebGL(),
});

// --- GUI --------------------------------------------------------------------------------

const gui = new GUI({ container: $('gui'), title: 'Case', width: 320 });
const controllers = new Map();  // target name (as in errors) -> lil-gui controller

const csProxy = {};
function defineProxy(obj, key, get, set) {
  Object.defineProperty(obj, key, { get, set, enumerable: true, configurable: true });
}
// Getters run before a case exists (updateDisplay at start): fall back to empty objects.
const cs = () => state.case?.controlSpace ?? {};
const opts = () => (state.case ? (state.case.options ??= {}) : {});
defineProxy(csProxy, 'kind', () => cs().kind ?? 'quadtree', (v) => { cs().kind = v; });
defineProxy(csProxy, 'interpolation', () => cs().interpolation ?? 'bilinear', (v) => { cs().interpolation = v; });
defineProxy(csProxy, 'hmin', () => cs().hmin ?? 0, (v) => { cs().hmin = v; });
defineProxy(csProxy, 'hmax', () => cs().hmax ?? 0.1, (v) => { cs().hmax = v; });
defineProxy(csProxy, 'smoothing', () => cs().gradation != null, (v) => {
  cs().gradation = v ? (state.lastDr ?? 2) : null;
  controllers.get('gradation').disable(!v);
});
defineProxy(csProxy, 'dr', () => cs().gradation ?? state.lastDr ?? 2, (v) => { state.lastDr = v; if (cs().gradation != null) cs().gradation = v; });
defineProxy(csProxy, 'quads', () => Boolean(opts().quads), (v) => { opts().quads = v; });
defineProxy(csProxy, 'allQuads', () => Boolean(opts().allQuads), (v) => { opts().allQuads = v; });
defineProxy(csProxy, 'maxElements', () => opts().maxElements ?? 2000000, (v) => { opts().maxElements = Math.round(v); });

// Surface cases: the "metric" options (examples/SURFACE_FORMAT.md), all in 3D units.
// Read without creating the section (the getters run for planar cases too); set creates it.
const sm = () => state.case?.metric ?? {};
const smSet = (key, v) => { (state.case.metric ??= {})[key] = v; };
const smProxy = {};
defineProxy(smProxy, 'chordTolerance', () => sm().chordTolerance ?? 0.01, (v) => smSet('chordTolerance', v));
defineProxy(smProxy, 'hmin', () => sm().hmin ?? 0.001, (v) => smSet('hmin', v));
defineProxy(smProxy, 'hmax', () => sm().hmax ?? 1, (v) => smSet('hmax', v));
defineProxy(smProxy, 'maxAspectRatio', () => sm().maxAspectRatio ?? 10, (v) => smSet('maxAspectRatio', v));
defineProxy(smProxy, 'smoothing', () => sm().gradation !== null, (v) => {
  smSet('gradation', v ? (state.lastSurfaceDr ?? 2) : null);
  controllers.get('metric.gradation').disable(!v);
});
defineProxy(smProxy, 'dr', () => sm().gradation ?? state.lastSurfaceDr ?? 2, (v) => { state.lastSurfaceDr = v; if (sm().gradation !== null) smSet('gradation', v); });
defineProxy(smProxy, 'adaptation', () => state.case?.adaptation ?? true, (v) => { state.case.adaptation = v; });
const fSm = gui.addFolder('Surface metric');
controllers.set('metric.chordTolerance', fSm.add(smProxy, 'chordTolerance').min(0).name('chord tolerance').onFinishChange(() => edited()));
controllers.set('metric.hmin', fSm.add(smProxy, 'hmin').min(0).name('hmin (3D)').onFinishChange(() => edited()));
controllers.set('metric.hmax', fSm.add(smProxy, 'hmax').min(0).name('hmax (3D)').onFinishChange(() => edited()));
controllers.set('metric.maxAspectRatio', fSm.add(smProxy, 'maxAspectRatio').min(1).name('d_max (aspect)').onFinishChange(() => edited()));
controllers.set('metric.smoothing', fSm.add(smProxy, 'smoothing').name('gradation on').onChange(() => edited()));
controllers.set('metric.gradation', fSm.add(smProxy, 'dr', 1, 16, 0.5).name('gradation dr').onFinishChange(() => edited()));
controllers.set('adaptation', fSm.add(smProxy, 'adaptation').name('adapt across shared').onChange(() => edited()));
fSm.hide();
const surfaceEditor = createSurfaceEditor({
  gui, controllers, getCase: () => state.case, edited: (d) => edited(d),
  onReplace: () => { needsFit = true; showEditable(); },
  // Another patch shown: its sources are the ones edited.
  onPatch: () => {
    state.selected = sourceList().length ? 0 : -1;
    rebuildSourceGui();
    views.sourcePatch = surfaceEditor.patch;
    views.setSources(sourceList(), state.selected, state.view.sources);
  },
});
surfaceEditor.folder.hide();

const fCs = gui.addFolder('Control space');
controllers.set('kind', fCs.add(csProxy, 'kind', ['quadtree', 'background']).name('structure').onChange(() => edited()));
controllers.set('interpolation', fCs.add(csProxy, 'interpolation', ['bilinear', 'serendipity']).name('interpolation').onChange(() => edited()));
controllers.set('hmin', fCs.add(csProxy, 'hmin').min(0).name('hmin').onFinishChange(() => edited()));
controllers.set('hmax', fCs.add(csProxy, 'hmax').min(0).name('hmax').onFinishChange(() => edited()));
controllers.set('smoothing', fCs.add(csProxy, 'smoothing').name('gradation on').onChange(() => edited()));
controllers.set('gradation', fCs.add(csProxy, 'dr', 1, 16, 0.5).name('gradation dr').onFinishChange(() => edited()));
const fOpt = gui.addFolder('Mesh options');
controllers.set('quads', fOpt.add(csProxy, 'quads').name('quad-dominant').onChange(() => edited()));
controllers.set('allQuads', fOpt.add(csProxy, 'allQuads').name('all quads').onChange(() => edited()));
controllers.set('maxElements', fOpt.add(csProxy, 'maxElements').min(1).step(1).name('max elements').onFinishChange(() => edited()));

// Sources: a selector, add/remove, and the selected source's fields.
const fSrc = gui.addFolder('Metric sources');
const srcPick = { source: -1 };
const srcActions = {
  addRadial() { addSource('radial'); },
  addSegment() { addSource('segment'); },
  remove() { removeSource(state.selected); },
};
let srcSelector = null;
fSrc.add(srcActions, 'addRadial').name('+ radial source');
fSrc.add(srcActions, 'addSegment').name('+ segment source');
const removeCtrl = fSrc.add(srcActions, 'remove').name('− remove selected');
let sourceGui = fSrc.addFolder('Selected source');

const fDisp = gui.addFolder('Display');
fDisp.add(state.view, 'view', { '2D': '2d', '2D | 3D': 'split', '3D': '3d' }).name('view').onChange(applyViewMode);
fDisp.add(state.view, 'colorBy', { 'element quality': 'quality', 'field (adaptation)': 'field', none: 'none' }).name('faces').onChange(restyle);
fDisp.add(state.view, 'edges', { 'metric length': 'length', plain: 'plain', off: 'off' }).name('edges').onChange(restyle);
fDisp.add(state.view, 'controlSpace').name('control space').onChange(restyle);
fDisp.add(state.view, 'sources').name('sources').onChange(restyle);
fDisp.add(state.view, 'lift', 0, 1, 0.05).name('3D lift by log h').onChange(restyle);

const fmtNum = (x) => (Math.abs(x) >= 100 || x === Math.round(x) ? String(Math.round(x * 1e6) / 1e6) : Number(x.toPrecision(4)).toString());

function rebuildSourceGui() {
  sourceGui.destroy();
  srcSelector?.destroy();
  for (const k of [...controllers.keys()]) if (k.startsWith('src:')) controllers.delete(k);
  const sources = sourceList();
  const labels = {};
  sources.forEach((s, i) => { labels[`${i + 1}: ${s.type === 'analytic' ? s.field : s.type}`] = i; });
  if (!sources.length) labels['(none)'] = -1;
  srcPick.source = state.selected;
  srcSelector = fSrc.add(srcPick, 'source', labels).name('selected').onChange((i) => selectSource(i));
  // Keep the selector first in the folder.
  fSrc.$children.prepend(srcSelector.domElement);
  controllers.set('src:', srcSelector);
  removeCtrl.disable(state.selected < 0);
  sourceGui = fSrc.addFolder(state.selected >= 0 ? `Source ${state.selected + 1}` : 'Selected source');
  const s = sources[state.selected];
  if (!s) return;
  const o = {};
  const num = (path, label, { deg = false, min = 0 } = {}) => {
    const keys = path.split('.');
    const parent = () => keys.slice(0, -1).reduce((a, k) => a[k], s);
    const last = keys[keys.length - 1];
    defineProxy(o, path, () => {
      const v = parent()[last] ?? 0;
      return deg ? Math.round(v * 180 / Math.PI * 1e4) / 1e4 : v;
    }, (v) => { parent()[last] = deg ? v * Math.PI / 180 : v; });
    const c = sourceGui.add(o, path).name(label).onFinishChange(() => edited());
    if (min !== null) c.min(min);
    controllers.set(`src:${path}`, c);
  };
  const point = (key, label) => {
    for (const [j, axis] of [[0, 'x'], [1, 'y']]) {
      defineProxy(o, `${key}.${axis}`, () => s[key][j], (v) => { s[key] = j ? [s[key][0], v] : [v, s[key][1]]; });
      const c = sourceGui.add(o, `${key}.${axis}`).name(`${label} ${axis}`).onFinishChange(() => edited());
      controllers.set(`src:${key}`, c);
    }
  };
  if (s.type === 'radial' || s.type === 'segment') {
    if (s.type === 'radial') point('center', 'center');
    else { point('p1', 'p1'); point('p2', 'p2'); }
    s.metric.h2 ??= s.metric.h1;
    s.metric.alpha ??= 0;
    num('metric.h1', 'h1 (along alpha)');
    num('metric.h2', 'h2 (normal)');
    num('metric.alpha', 'alpha (deg)', { deg: true, min: null });
    num('radius', 'radius');
  } else if (s.field === 'point') {
    point('center', 'center'); num('h0', 'h0'); num('growth', 'growth');
  } else if (s.field === 'shear_layer_circle') {
    point('center', 'center'); num('radius', 'radius'); num('h0', 'h0 (across)'); num('hTangent', 'h tangent'); num('thickness', 'thickness');
  } else if (s.field === 'boundary_layer') {
    point('p1', 'wall p1'); point('p2', 'wall p2'); num('h0', 'h0 (at wall)'); num('hTangent', 'h tangent'); num('thickness', 'thickness');
  }
}

function selectSource(i) {
  if (i === state.selected) return;
  state.selected = i;
  rebuildSourceGui();
  views.setSources(sourceList(), state.selected, state.view.sources);
  saveUrlSoon();
}

function domainBounds() {
  return views.meshBounds2() ?? [0, 0, 1, 1];
}

function addSource(type) {
  if (state.surface) {
    // On a surface the next click on it (3D view) or in (u, v) places the source.
    views.placing = type;
    statusText.textContent = `click on the surface (3D) or in (u, v) to place the ${type} source`;
    return;
  }
  const [x0, y0, x1, y1] = domainBounds();
  const size = Math.max(x1 - x0, y1 - y0);
  const cx = Math.min(Math.max(views.view2.cx, x0), x1), cy = Math.min(Math.max(views.view2.cy, y0), y1);
  const hmax = cs().hmax;
  const r = (x) => Number(x.toPrecision(3));
  const metric = { alpha: 0, h1: r(hmax / 10), h2: r(hmax / 3) };
  const s = type === 'radial'
    ? { type, center: [r(cx), r(cy)], metric, radius: r(size / 8) }
    : { type, p1: [r(cx - size / 6), r(cy)], p2: [r(cx + size / 6), r(cy)], metric: { alpha: 0, h1: r(hmax / 2), h2: r(hmax / 12) }, radius: r(size / 25) };
  (state.case.sources ??= []).push(s);
  state.selected = state.case.sources.length - 1;
  rebuildSourceGui();
  edited(0);
}

// A source placed on a surface patch at (u, v) (a click in either view): sizes in the
// patch's parameter units, from its extent in the 2D layout.
function placeSource(hit) {
  const type = views.placing;
  views.placing = null;
  if (!type || !state.surface) return;
  if (hit.patch !== surfaceEditor.patch) surfaceEditor.select(hit.patch);
  const L = views.layout;
  const [x0, y0, x1, y1] = L ? [L.ranges[hit.patch][0], L.bounds[1], L.ranges[hit.patch][1], L.bounds[3]] : domainBounds();
  const size = Math.max(x1 - x0, y1 - y0);
  const r = (x) => Number(x.toPrecision(3));
  const [u, v] = hit.uv.map(r);
  const s = type === 'radial'
    ? { type, center: [u, v], metric: { alpha: 0, h1: r(size / 80), h2: r(size / 80) }, radius: r(size / 10) }
    : { type, p1: [r(u - size / 8), v], p2: [r(u + size / 8), v], metric: { alpha: 0, h1: r(size / 40), h2: r(size / 150) }, radius: r(size / 30) };
  sourceList({ create: true }).push(s);
  state.selected = sourceList().length - 1;
  state.lastPlaced = { ...hit, source: state.selected };
  rebuildSourceGui();
  edited(0);
}

function removeSource(i) {
  if (i < 0) return;
  const sources = sourceList();
  sources.splice(i, 1);
  state.selected = Math.min(i, sources.length - 1);
  rebuildSourceGui();
  edited(0);
}

// --- inline errors ----------------------------------------------------------------------

const inlineErrors = [];
function clearErrors() {
  $('view-error').hidden = true;
  for (const e of inlineErrors.splice(0)) {
    e.el.remove?.();
    e.ctrl?.domElement.classList.remove('has-error');
    if (e.fixed) e.fixed.hidden = true;
  }
}

/** Shows message next to the control named by target (see state.errorTarget). */
function showError(target, message) {
  const fixedBoxes = { domain: $('error-domain'), case: $('error-case') };
  if (fixedBoxes[target]) {
    const box = fixedBoxes[target];
    box.textContent = message;
    box.hidden = false;
    if (target === 'domain') $('domain-box').open = true;
    inlineErrors.push({ el: {}, fixed: box });
    return box;
  }
  let ctrl = controllers.get(target);
  const src = /^sources\[(\d+)\](?:\.(.*))?$/.exec(target);
  if (src) {
    const i = Number(src[1]);
    fSrc.open();
    if (i !== state.selected && i < sourceList().length) {
      state.selected = i;
      rebuildSourceGui();
      views.setSources(sourceList(), state.selected, state.view.sources);
    }
    const field = src[2] ?? '';
    ctrl = controllers.get(`src:${field}`) ?? controllers.get(`src:${field.split('.')[0]}`) ?? controllers.get('src:');
  }
  if (!ctrl) return showError('case', message);
  ctrl.parent.open();
  const el = document.createElement('div');
  el.className = 'inline-error';
  el.setAttribute('role', 'alert');
  el.dataset.target = target;
  el.textContent = message;
  ctrl.domElement.after(el);
  ctrl.domElement.classList.add('has-error');
  inlineErrors.push({ el, ctrl });
  return el;
}

// --- meshing ----------------------------------------------------------------------------

let editTimer = null;
let needsFit = true;

/** A new version of the case (an edit): stamps when it was made, for the latency figures. */
function bumpVersion() {
  state.caseVersion++;
  state.editAt = wallNow();
  views.setSources(sourceList(), state.selected, state.view.sources);
  saveUrlSoon();
}

/** The case changed: remesh after delay ms (a newer edit restarts the wait; a running job is superseded). */
function edited(delay = EDIT_DEBOUNCE_MS) {
  bumpVersion();
  recordHistory();
  refreshEditable();
  clearTimeout(editTimer);
  editTimer = setTimeout(() => { editTimer = null; remesh(); cancelStaleLanes(); }, delay);
}

// While a handle is dragged: remesh at once when the worker is free (leading edge, no
// debounce wait); when a job is running, let it finish and draw (the mesh follows the
// drag) and then start the latest input right away. Releasing the handle supersedes a
// stale job (see onDrag).
// When the pointer rests while a stale job runs, that job is superseded so the resting
// position does not wait for it. Resting: no move for 1.5 times the recent interval
// between moves (at least 30 ms; the browser sends at most one move per frame, and a
// loaded page draws few frames).
let dragWaiting = false, restTimer = null, lastMoveAt = 0, moveInterval = 16;
function editedByDrag() {
  bumpVersion();
  refreshEditable();
  clearTimeout(restTimer);
  const now = performance.now();
  if (now - lastMoveAt < 500) moveInterval = 0.7 * moveInterval + 0.3 * (now - lastMoveAt);
  lastMoveAt = now;
  const lanes = readyLanes();
  if (editTimer === null && (lanes.length > 1 || !meshRunner.busy)) {
    remesh(runnerForLatest(lanes));
    return;
  }
  dragWaiting = true;
  restTimer = setTimeout(() => {
    restTimer = null;
    if (dragWaiting && state.runningVersion !== state.caseVersion) {
      dragWaiting = false;
      remesh(runnerForLatest());
    }
  }, Math.max(30, 1.5 * moveInterval));
}

// The latest input of a drag waited for the worker: start it now.
function startWaitingDrag() {
  if (!dragWaiting) return;
  dragWaiting = false;
  remesh(runnerForLatest());
}

// The surface case's key for its curvature stages (all but the patches' 2D sources, which
// a drag moves), or null for a planar case (nothing to warm).
function stagesKey(c) {
  if (!state.surface || !Array.isArray(c?.patches)) return null;
  return JSON.stringify({ ...c, patches: c.patches.map(({ sources, ...rest }) => rest) });
}

// The mesh lanes that can take an input now: the main runner, and the second lane once
// its worker is started and holds the case's curvature stages.
function readyLanes() {
  if (!laneRunner) return [meshRunner];
  const key = stagesKey(state.case);
  const ready = key === null ? laneRunner.slot.isReady : laneRunner.warmFor(key);
  return ready && laneRunner.cancelsInWorker ? [meshRunner, laneRunner] : [meshRunner];
}

// The runner for the latest input: an idle lane, else the one running the newer job (it is
// superseded; the older one finishes and is drawn, so the mesh follows the drag).
function runnerForLatest(lanes = readyLanes()) {
  const idleLane = lanes.find((r) => !r.busy);
  if (idleLane) return idleLane;
  return lanes.reduce((a, b) => ((b.jobVersion ?? -1) > (a.jobVersion ?? -1) ? b : a));
}

// Released: jobs for inputs older than the last one are stopped (the CPU goes to the last
// one's); returns whether the last input's job is already running.
function cancelStaleLanes() {
  const lanes = laneRunner ? [meshRunner, laneRunner] : [meshRunner];
  const running = lanes.some((r) => r.busy && r.jobVersion === state.caseVersion);
  if (!running) return false;
  for (const r of lanes) {
    if (r.busy && r.jobVersion !== state.caseVersion && r.cancelsInWorker) {
      r.cancelAll();
      state.cancelled++;
    }
  }
  return true;
}

/** Wants the control-space overlay from the worker (it costs an inspection of the structure). */
const wantOverlay = () => Boolean(state.view.controlSpace);

// A surface case's curvature stages depend on everything but the patches' 2D sources
// (what a drag moves): the spare worker builds them once per such key, after a mesh is
// drawn, so the worker a cancellation swaps in does not start cold.
// The second mesh lane starts here (after the first mesh, not competing with it) and is
// warmed the same way.
function warmLanes(c) {
  if (!laneRunner && laneCount > 1 && meshRunner.cooperative) laneRunner = new JobRunner({ supersede: true, spare: false });
  const key = stagesKey(c);
  if (key === null) return;
  meshRunner.warmSpare(key, 'warm', { case: c });
  if (laneRunner && !laneRunner.busy) laneRunner.ready.then(() => laneRunner.warm(key, 'warm', { case: c }));
}

let completionWaiters = [];
async function remesh(runner = runnerForLatest()) {
  const version = state.caseVersion;
  const editAt = state.editAt ?? wallNow();
  try {
    checkCase(state.case);
  } catch (e) {
    if (!(e instanceof InputError)) throw e;
    fail({ code: e.code, message: e.message, target: e.target }, version);
    return;
  }
  state.jobsStarted++;
  if (runner !== meshRunner) state.laneJobs++;
  const before = runner.restarts, cancelsBefore = runner.cancellations;
  const overlay = wantOverlay();
  state.runningVersion = version;
  // A surface mesh while a handle is held, and the one its release asks for, comes without
  // its colours (the per-element 3D measures: they follow with the report, a third of a
  // 50k-triangle run), so the mesh is drawn sooner.
  const held = Boolean(views.dragging || state.dragEndAt);
  const dragging = state.surface && held;
  // A drag's jobs post no progress messages (the toolbar is quiet; see quietToolbar).
  const job = runner.run('mesh', { case: state.case, surface: state.surface, overlay, dragging, progress: !held });
  runner.jobVersion = version;
  state.cancelled += runner.cancellations - cancelsBefore;
  if (runner.restarts > before) {
    const t0 = performance.now();
    runner.ready.then(() => state.workerRestartMs.push(Math.round(performance.now() - t0)));
  }
  try {
    const { id, result, marks, totalMs, workerMs, receivedAt } = await job;
    if (runner.jobVersion === version) runner.jobVersion = null;
    if (version <= state.meshedVersion) {
      // The other lane drew a newer input's mesh first: this one is not shown.
      state.staleResults++;
      if (state.runningVersion === version) state.runningVersion = null;
      state.jobsDone++;
      startWaitingDrag();
      settle();
      return;
    }
    const b = draw(result, version, editAt, marks, receivedAt, overlay);
    b.lane = runner === meshRunner ? 0 : 1;
    warmLanes(state.case);
    state.lastJob = { meshMs: Math.round(b.coreMs), workerMs: Math.round(workerMs), totalMs: Math.round(totalMs), drawMs: Math.round(b.geometryMs + b.renderMs) };
    state.lastError = null;
    clearErrors();
    if (status.classList.contains('err')) status.classList.remove('err');
    if (state.runningVersion === version) state.runningVersion = null;
    // While dragging, the next input goes first: the report of a mesh already left
    // behind is never computed. Otherwise the quality report follows.
    if (dragWaiting || (state.runningVersion ?? -1) > version) {
      state.jobsDone++;
      startWaitingDrag();
      return;
    }
    let stats = result.stats;
    if (!stats) {
      const r = await runner.run('report', { of: id });
      stats = r.result.stats;
      b.reportMs = r.result.reportMs;
      // A surface mesh made while dragging: its colours, if it is still the one shown.
      if (r.result.measures && views.result === result) {
        Object.assign(result.measures, r.result.measures);
        views.setStyle(styleOf());
        state.recolours++;
      }
    }
    const t0 = wallNow();
    state.lastStats = stats;
    renderStats(stats);
    renderHistograms(state.lastMeasures, stats);
    renderLegend();
    b.afterDrawMs = wallNow() - t0;
    const ps = stats.pipelineSeconds;
    if (ps) Object.assign(b, { coreControlSpaceMs: 1000 * ps.controlSpace, coreUpdatesMs: 1000 * ps.boundaryUpdates, coreMeshingMs: 1000 * ps.meshing });
    for (const k of Object.keys(b)) if (typeof b[k] === 'number') b[k] = Math.round(b[k] * 10) / 10;
    state.jobsDone++;
    if (!toolbarQuiet) statusText.textContent = `meshed in ${(b.inputToDrawnMs / 1000).toFixed(2)} s`;
    settle();
  } catch (e) {
    if (runner.jobVersion === version) runner.jobVersion = null;
    if (state.runningVersion === version) state.runningVersion = null;
    if (e instanceof CancelledError) return;
    const target = (state.surface && surfaceEditor.targetOf(e.message)) || errorTarget(e.code, e.message);
    fail({ code: e.code ?? 'INTERNAL', message: e.message, target }, version);
    startWaitingDrag();  // a drag goes on past an input the core rejects
  }
}

/**
 * Puts a mesh from the worker on screen and returns where the time went, in ms:
 *   inputToPostMs   the edit -> the job posted (waiting for a busy worker while dragging)
 *   postToStartMs   the job posted -> the worker starts it (message; a worker start-up)
 *   coreMs          the core in the worker: case run + copying out + measures
 *     coreRunMs, coreOutputMs, coreMeasuresMs (and, once the report is in, coreControlSpaceMs,
 *     coreUpdatesMs, coreMeshingMs from its pipelineSeconds)
 *   toPageMs        the core done -> the result in the page (overlay, transfer):
 *     resultOutMs (the worker: the result object, the last run freed, the post) and
 *     messageMs (posted -> the page's handler runs: the page's main thread was busy)
 *   geometryMs      page: the geometry (and overlay) rebuilt
 *   renderMs        page: drawing the 2D view (GPU uploads included; with state.syncDraw
 *                   until the GPU has finished it). The 3D view follows on the next frame.
 *   inputToDrawnMs  the edit -> the 2D view drawn
 * reportMs (the quality report, a separate job) and afterDrawMs (numbers, histograms)
 * follow once the report is in.
 */
function draw(result, version, editAt, marks, receivedAt, overlay) {
  const t0 = wallNow();
  state.overlayShown = overlay;
  showResult(result);
  const t1 = wallNow();
  // Draw the view being edited now and the other one on the next frame: on a software
  // rasterizer the two cost about the same, and the 2D view is where the handle moves.
  // While a handle is held the 3D view is not redrawn at all (it would only queue work
  // for the rasterizer that the next mesh makes stale); it catches up on release.
  views.renderNow(views.dragging ? [views.dragView ?? '2d'] : ['2d', '3d'], { sync: state.syncDraw });
  const t2 = wallNow();
  state.meshedVersion = version;
  state.drawnVersions.push(version);
  if (state.drawnVersions.length > 50) state.drawnVersions.shift();
  state.meshesDrawn++;
  const core = result.core ?? {};
  const b = {
    version,
    triangles: result.mesh.triangles.length / 3,
    quads: result.mesh.quads.length / 4,
    inputToPostMs: marks.posted - editAt,
    postToStartMs: marks.ready - marks.posted,
    coreMs: marks.coreEnd - marks.coreStart,
    coreRunMs: core.runMs,
    coreOutputMs: core.outputMs,
    coreMeasuresMs: core.measuresMs,
    toPageMs: receivedAt - marks.coreEnd,
    resultOutMs: marks.resultPosted - marks.coreEnd,
    messageMs: receivedAt - marks.resultPosted,
    geometryMs: t1 - t0,
    renderMs: t2 - t1,
    inputToDrawnMs: t2 - editAt,
  };
  for (const k of Object.keys(b)) if (typeof b[k] === 'number') b[k] = Math.round(b[k] * 10) / 10;
  state.lastBreakdown = b;
  state.breakdowns.push(b);
  if (state.breakdowns.length > 50) state.breakdowns.shift();
  if (state.dragEndAt && version >= state.dragEndVersion) {
    state.dragToMeshMs = Math.round(t2 - state.dragEndAt);
    state.dragInputToMeshMs = Math.round(t2 - (state.dragLastEditAt ?? state.dragEndAt));
    b.drag = true;
    state.dragEndAt = null;
    quietToolbar(false);
  }
  return b;
}

function fail(error, version) {
  state.jobsFailed++;
  state.lastError = error;
  clearErrors();
  showError(error.target, `${error.code}: ${error.message}`);
  // Also at the top of the view, where it is seen whatever the panel's scroll position.
  const banner = $('view-error');
  banner.textContent = `${error.code}: ${error.message}${state.lastStats ? ' (previous mesh shown)' : ''}`;
  banner.hidden = false;
  // The previous mesh stays on screen; the status says it is not the current input.
  statusText.textContent = state.lastStats ? 'input error · previous mesh shown' : 'input error';
  status.classList.add('err');
  state.meshedVersion = version;
  settle();
}

function settle() {
  if (!idle()) return;
  for (const w of completionWaiters.splice(0)) w();
}

function idle() {
  return editTimer === null && !meshRunner.busy && !laneRunner?.busy && !dragWaiting && !state.adapting;
}

// The mesh part of a result on screen (the quality report and the histograms follow
// when the report arrives).
function showResult(result) {
  if (result.mesh.dimension === 3 || state.surface) state.view.view === '2d' && applyViewMode('split');
  views.setMesh(result, styleOf(result));
  views.setControlSpace(result.overlay, state.view.controlSpace);
  state.overlay = result.overlay;
  state.lastMeasures = result.measures;
  if (needsFit) {
    needsFit = false;
    views.fit2D(views.meshBounds2());
    views.fit3D();
  } else if (!views.dragging) {
    views.refitIfOutgrown();
  }
  views.sourcePatch = state.surface ? surfaceEditor.patch : 0;
  views.setSources(sourceList(), state.selected, state.view.sources);
}

function styleOf(result = views.result) {
  // The field colours only adapted meshes (the adaptation mode); a case's mesh shows its quality.
  const colorBy = state.view.colorBy === 'field' && !result?.measures?.field ? 'quality' : state.view.colorBy;
  return { colorBy, edges: state.view.edges, lift: state.view.lift };
}

function restyle() {
  // The overlay is inspected only when shown: turning it on remeshes with it.
  if (wantOverlay() && !state.overlayShown && state.case && views.mesh) edited(0);
  views.setStyle(styleOf());
  views.setControlSpace(state.overlay, state.view.controlSpace);
  views.setSources(sourceList(), state.selected, state.view.sources);
  renderLegend();
  saveUrlSoon();
}

function applyViewMode(mode) {
  state.view.view = mode;
  views.setMode(mode);
  $('view').classList.toggle('split', mode === 'split');
  $('label-2d').hidden = mode === '3d';
  $('label-3d').hidden = mode === '2d';
  for (const b of document.querySelectorAll('#view-mode button')) b.classList.toggle('on', b.dataset.mode === mode);
  gui.controllersRecursive().forEach((c) => c.updateDisplay());
  if (views.mesh) {
    views.fit2D(views.meshBounds2());
    views.fit3D();
  }
  saveUrlSoon();
}

// --- numbers and plots ------------------------------------------------------------------

function renderStats(s) {
  const pct = (x) => (x == null ? '–' : `${(100 * x).toFixed(1)} %`);
  const f3 = (x) => (x == null ? '–' : Number(x).toFixed(3));
  const el = s.edgeLength ?? {}, q = s.quality ?? {};
  const ms = (x) => `${(1000 * (x ?? 0)).toFixed(0)} ms`;
  // A surface's report measures in 3D (quality3d: its edge count, no degenerate count and
  // no [0.6, 1.3] fraction): rows it has no value for are left out, not shown empty.
  const surface = s.quality3d != null;
  const rows = [
    ['vertices', s.vertices], ['triangles', s.triangles],
    ['quads', s.quads], ['edges', s.edges ?? s.quality3d?.edges],
    ['len in [1/√2, √2]', pct(el.fractionWithinSqrt2)],
    ...(surface ? [] : [['len in [0.6, 1.3]', pct(el['fractionWithin0.6_1.3'])]]),
    ['len min / mean', `${f3(el.min)} / ${f3(el.mean)}`], ['len max', f3(el.max)],
    ['Q min / mean', `${f3(q.min)} / ${f3(q.mean)}`],
    surface ? ['inverted', `${s.inverted ?? '–'}`] : ['inverted, degen.', `${s.inverted ?? '–'}, ${s.degenerate ?? '–'}`],
    ...(s.pipelineSeconds
      ? [['core control space', ms(s.pipelineSeconds.controlSpace + s.pipelineSeconds.boundaryUpdates)], ['core meshing', ms(s.pipelineSeconds.meshing)]]
      : [['core total', ms(s.secondsTotal)], ['patches, rounds', `${s.patches ?? '–'}, ${s.rounds ?? '–'}`]]),
    ['job round trip', state.lastJob ? `${state.lastJob.totalMs} ms` : '…'], ['cancelled jobs', state.cancelled],
  ];
  const q3 = s.quality3d;
  if (q3) {
    rows.push(['chord dev. max', `${Number(q3.chordDeviationMax).toPrecision(3)} (${f3(q3.chordDeviationMaxRelative)} tol.)`]);
    if (s.sharedEdges) rows.push(['shared edges, size ratio', `${s.sharedEdges}, ${f3(s.crossSharedSizeRatioMax)}`]);
  }
  if (s.notes?.length) rows.push(['core notes', s.notes.join('; ')]);
  const dl = $('stats');
  dl.replaceChildren();
  for (const [k, v] of rows) {
    const dt = document.createElement('dt'), dd = document.createElement('dd');
    dt.textContent = k;
    dd.textContent = v;
    dd.title = String(v);  // long notes are cut with an ellipsis
    dd.dataset.key = k;
    if ((k.startsWith('inverted') && (s.inverted || s.degenerate))) dd.className = 'bad';
    dl.append(dt, dd);
  }
}

function renderHistograms(m, stats) {
  drawHistogram($('hist-length'), m?.edgeLength, {
    lo: 0, hi: 2, bins: 48, title: state.surface ? '3D metric edge length' : 'metric edge length',
    color: (x) => css(lengthColor(x)), band: [Math.SQRT1_2, Math.SQRT2], ticks: [0, 0.5, 1, 1.5, 2], marker: stats.edgeLength?.mean,
  });
  drawHistogram($('hist-quality'), m?.quality, {
    lo: 0, hi: 1, bins: 40, title: state.surface ? 'element quality Q (3D metric)' : 'element quality Q (metric)',
    color: (x) => css(qualityColor(x)), ticks: [0, 0.25, 0.5, 0.75, 1], marker: stats.quality?.mean,
  });
}

function ramp(fn, lo, hi) {
  const stops = Array.from({ length: 9 }, (_, i) => css(fn(lo + ((hi - lo) * i) / 8)));
  return `<span class="ramp" style="background: linear-gradient(90deg, ${stops.join(',')})"></span>`;
}

function renderLegend() {
  const parts = [];
  if (state.view.colorBy === 'quality') parts.push(`quality 0${ramp(qualityColor, 0, 1)}1`);
  const field = state.lastMeasures?.field;
  if (state.view.colorBy === 'field' && field) {
    let lo = Infinity, hi = -Infinity;
    for (const v of field) lo = Math.min(lo, v), hi = Math.max(hi, v);
    parts.push(`u ${lo.toPrecision(2)}${ramp(fieldColor, 0, 1)}${hi.toPrecision(2)}`);
  }
  if (state.view.edges === 'length') parts.push(`edge length ½${ramp(lengthColor, 0.5, 2)}2`);
  const cl = views.controlLegend;
  if (state.view.controlSpace && cl) parts.push(`control space h ${cl.hmin.toPrecision(2)}${ramp(sizeColor, 0, 1)}${cl.hmax.toPrecision(2)} (${cl.count} ${state.overlay?.glyphs ? 'ellipses' : state.overlay?.sampled ? 'samples' : 'nodes'})`);
  $('legend').innerHTML = parts.join(' &nbsp; ');
}

// --- presets, case, URL -----------------------------------------------------------------

function fillPresetSelect() {
  const sel = $('preset');
  sel.replaceChildren();
  for (const group of ['planar', 'surface']) {
    const list = presets.filter((p) => p.group === group);
    if (!list.length) continue;
    const og = document.createElement('optgroup');
    og.label = group === 'planar' ? 'Planar' : 'Surfaces';
    for (const p of list) og.append(new Option(p.label, p.id));
    sel.append(og);
  }
  sel.append(new Option('(custom case)', 'custom'));
  sel.addEventListener('change', () => { if (sel.value !== 'custom') loadPreset(sel.value); });
}

function firstEditableSource(c) {
  return (c.sources ?? []).findIndex((s) => s.type === 'radial' || s.type === 'segment');
}

/** Replaces the case (preset, file or URL) and remeshes. */
function setCase(c, { presetId = 'custom', selected = null, surface = null, fit = true, patch = 0 } = {}) {
  state.case = structuredClone(c);
  state.presetId = presetId;
  state.surface = surface ?? (Boolean(presetById(presetId)?.surface) || Array.isArray(c.patches));
  // Planar cases carry a control space section; surface cases have their own "metric" options.
  if (!state.surface) state.case.controlSpace ??= { hmax: 0.1 };
  if (state.surface) surfaceEditor.reset(Math.min(patch, (state.case.patches?.length ?? 1) - 1));
  const first = firstEditableSource(state.surface ? state.case.patches?.[0] ?? {} : state.case);
  state.selected = selected ?? (first >= 0 ? first : (sourceList().length ? 0 : -1));
  if (!state.surface && state.case.controlSpace.gradation != null) state.lastDr = state.case.controlSpace.gradation;
  $('preset').value = presetId;
  showEditable();
  // The planar controls edit fields that surface cases do not have (and the other way round).
  fCs.show(!state.surface);
  fSm.show(state.surface);
  surfaceEditor.folder.show(state.surface);
  if (state.surface) surfaceEditor.rebuild();
  rebuildSourceGui();
  gui.controllersRecursive().forEach((ctrl) => ctrl.updateDisplay());
  controllers.get('gradation').disable(state.surface || state.case.controlSpace.gradation == null);
  controllers.get('metric.gradation').disable(!state.surface || state.case.metric?.gradation === null);
  if (fit) needsFit = true;
  clearErrors();
  edited(0);
}

// --- undo / redo ------------------------------------------------------------------------
// Every edit that remeshes (panel, drag release, new case) is a step; a drag is one step.
const edits = { past: [], future: [], current: null, applying: false };
const HISTORY_STEPS = 200;
function recordHistory() {
  if (edits.applying || !state.case) return;
  const snapshot = JSON.stringify({ c: state.case, p: state.presetId, surface: state.surface, patch: surfaceEditor.patch });
  if (snapshot === edits.current) return;
  if (edits.current !== null) edits.past.push(edits.current);
  if (edits.past.length > HISTORY_STEPS) edits.past.shift();
  edits.current = snapshot;
  edits.future = [];
}
function applyHistory(snapshot) {
  const { c, p, surface, patch } = JSON.parse(snapshot);
  edits.applying = true;
  try {
    setCase(c, { presetId: p, surface, selected: state.selected, fit: false, patch });
  } finally {
    edits.applying = false;
  }
  edits.current = snapshot;
}
function undo() {
  if (!edits.past.length) return false;
  edits.future.push(edits.current);
  applyHistory(edits.past.pop());
  return true;
}
function redo() {
  if (!edits.future.length) return false;
  edits.past.push(edits.current);
  applyHistory(edits.future.pop());
  return true;
}
$('undo').addEventListener('click', () => undo());
$('redo').addEventListener('click', () => redo());
document.addEventListener('keydown', (e) => {
  if (!(e.ctrlKey || e.metaKey)) return;
  const t = e.target;
  if (t && (t.tagName === 'INPUT' || t.tagName === 'TEXTAREA' || t.isContentEditable)) return;  // the field's own undo
  const k = e.key.toLowerCase();
  if (k === 'z' && !e.shiftKey) { if (undo()) e.preventDefault(); } else if ((k === 'z' && e.shiftKey) || k === 'y') { if (redo()) e.preventDefault(); }
});

async function loadPreset(id) {
  const p = presetById(id) ?? presetById(defaultPresetId);
  try {
    setCase(await p.load(), { presetId: p.id, surface: p.surface });
  } catch (e) {
    showError('case', `cannot load preset: ${e.message}`);
  }
}

let urlTimer = null;
function saveUrlSoon() {
  clearTimeout(urlTimer);
  urlTimer = setTimeout(async () => {
    if (!state.case) return;
    const hash = await encodeState({ p: state.presetId, c: state.case, v: state.view, s: state.selected });
    history.replaceState(null, '', hash);
  }, 250);
}

async function restoreFromUrl() {
  try {
    const s = await decodeState(location.hash);
    if (!s) return false;
    Object.assign(state.view, defaultView(), s.v ?? {});
    setCase(s.c, { presetId: s.p ?? 'custom', selected: s.s ?? null });
    return true;
  } catch (e) {
    showError('case', `could not read the state in the link (${e.message}); loaded the default preset`);
    return false;
  }
}

// --- downloads and file input -----------------------------------------------------------

function download(text, filename, type = 'text/plain') {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = Object.assign(document.createElement('a'), { href: url, download: filename });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

const baseName = () => (state.case?.name ?? state.presetId ?? 'anisomesh').replace(/[^\w.-]+/g, '_');

async function onDownload(kind) {
  const box = $('error-io');
  box.hidden = true;
  try {
    if (kind === 'case') return download(JSON.stringify(state.case, null, 2), `${baseName()}.json`, 'application/json');
    if (kind === 'cs-vtk' || kind === 'cs-json') {
      const format = kind === 'cs-vtk' ? 'vtk' : 'json';
      const { result } = await utilRunner.run('exportControlSpace', { case: state.case, format });
      // A surface case's VTK: one file per patch (each in its own (u, v) plane).
      if (Array.isArray(result)) return result.forEach((text, p) => download(text, `${baseName()}_control_space_patch${p}.${format}`));
      return download(result, `${baseName()}_control_space.${format}`);
    }
    if (!views.mesh) throw new Error('no mesh yet');
    const { result } = await utilRunner.run('writeMesh', { mesh: views.mesh, format: kind });
    download(result, `${baseName()}.${kind}`);
  } catch (e) {
    box.textContent = `${e.code ?? 'ERROR'}: ${e.message}`;
    box.hidden = false;
  }
}

for (const b of document.querySelectorAll('#downloads button')) b.addEventListener('click', () => onDownload(b.dataset.dl));

/** Opens a case file's text: a planar case ("domain") or a surface case ("patches"). */
function loadCaseText(text, name = 'case') {
  const box = $('error-io');
  box.hidden = true;
  try {
    const c = JSON.parse(text);
    if (!c || typeof c !== 'object' || Array.isArray(c) || !(c.domain || Array.isArray(c.patches))) {
      throw new Error('not a case: no "domain" (planar, examples/CASE_FORMAT.md) and no "patches" (surface, examples/SURFACE_FORMAT.md)');
    }
    setCase(c, { presetId: 'custom', surface: Array.isArray(c.patches) });
    return true;
  } catch (e) {
    box.textContent = `${name}: ${e.message}`;
    box.hidden = false;
    return false;
  }
}

/**
 * An SVG drawing as the domain of a new planar case (outer contour and holes, scaled so
 * the larger side is the size box's value; sizes hmax = size / 25, hmin = size / 500).
 */
async function loadSvgText(text, name = 'drawing.svg') {
  const box = $('error-io');
  box.hidden = true;
  const size = Number($('svg-size').value) || 1;
  try {
    const { result: domain } = await utilRunner.run('domainFromSvg', { text, size });
    const kind = !state.surface ? state.case?.controlSpace?.kind : undefined;
    const c = {
      name: name.replace(/\.svg$/i, ''),
      domain,
      controlSpace: { ...(kind ? { kind } : {}), hmin: size / 500, hmax: size / 25, gradation: 2 },
    };
    setCase(c, { presetId: 'custom', surface: false });
    return true;
  } catch (e) {
    box.textContent = `${name}: ${e.code ?? 'ERROR'}: ${e.message}`;
    box.hidden = false;
    return false;
  }
}
const isSvgFile = (file) => /\.svg$/i.test(file.name) || file.type === 'image/svg+xml';

$('svg-file').addEventListener('change', async (ev) => {
  const file = ev.target.files[0];
  ev.target.value = '';
  if (file) loadSvgText(await file.text(), file.name);
});

$('case-file').addEventListener('change', async (ev) => {
  const file = ev.target.files[0];
  ev.target.value = '';
  if (file) loadCaseText(await file.text(), file.name);
});

// A case file dropped anywhere on the page opens like "Load case .json".
document.addEventListener('dragover', (ev) => {
  if (![...(ev.dataTransfer?.types ?? [])].includes('Files')) return;
  ev.preventDefault();
  ev.dataTransfer.dropEffect = 'copy';
  document.body.classList.add('dropping');
});
document.addEventListener('dragleave', (ev) => { if (!ev.relatedTarget) document.body.classList.remove('dropping'); });
document.addEventListener('drop', async (ev) => {
  const file = ev.dataTransfer?.files?.[0];
  document.body.classList.remove('dropping');
  if (!file) return;
  ev.preventDefault();
  if (isSvgFile(file)) loadSvgText(await file.text(), file.name);
  else loadCaseText(await file.text(), file.name);
});

$('copy-link').addEventListener('click', async () => {
  const box = $('error-io');
  try {
    await navigator.clipboard.writeText(location.href);
    box.textContent = 'link copied';
  } catch {
    box.textContent = 'copy the address bar: it holds the whole state';
  }
  box.classList.remove('error');
  box.hidden = false;
  setTimeout(() => { box.hidden = true; box.classList.add('error'); }, 2500);
});

// JSON with the number arrays (points) kept on one line: short enough to edit by hand.
function domainText(d) {
  return JSON.stringify(d, null, 1)
    .replace(/\[\s+([-+\d.eE,\s]+?)\s+\]/g, (m, inner) => `[${inner.replace(/\s+/g, '')}]`)
    .replace(/\[\s+((?:\[[^[\]]*\],?\s*)+)\]/g, (m, inner) => `[${inner.replace(/\s+/g, '')}]`);
}

// The editable JSON part of the case: the planar domain (contour and holes), or a surface
// case's model: its patches (surfaces with their expressions, trimming contours, sources),
// the curves they share (a second patch and its shared curve are added here) and the named
// surfaces they use.
const SURFACE_MODEL_KEYS = ['surfaces', 'patches', 'shared'];
function editableValue() {
  if (!state.surface) return state.case.domain;
  return Object.fromEntries(SURFACE_MODEL_KEYS.filter((k) => state.case[k] !== undefined).map((k) => [k, state.case[k]]));
}
function setEditable(d) {
  if (!state.surface) {
    state.case.domain = d;
    return;
  }
  // An array is the patches alone (as the box held them before it held the whole model).
  const model = Array.isArray(d) ? { ...editableValue(), patches: d } : d;
  for (const k of SURFACE_MODEL_KEYS) {
    if (model?.[k] !== undefined) state.case[k] = model[k];
    else delete state.case[k];
  }
}
function showEditable() {
  $('domain-box').querySelector('summary').textContent = state.surface ? 'Surface model (JSON: patches, shared curves)' : 'Domain (JSON)';
  state.shownEditable = $('domain-json').value = domainText(editableValue());
  // The analytic size field h(x, y) is a planar source (surface patches take sources in (u, v)).
  $('expr-box').hidden = state.surface;
}
// The box follows the case (panel edits, sources placed or dragged) while the user has not
// typed in it: an Apply then never silently undoes an edit made elsewhere.
function refreshEditable() {
  if ($('domain-box').open && $('domain-json').value === state.shownEditable) showEditable();
}
$('domain-box').addEventListener('toggle', refreshEditable);

// Domain as editable JSON (a self-intersecting contour etc. is reported below the box).
$('domain-apply').addEventListener('click', () => {
  let d;
  try {
    d = JSON.parse($('domain-json').value);
  } catch (e) {
    clearErrors();
    showError('domain', `JSON: ${e.message}`);
    return;
  }
  setEditable(d);
  if (state.surface) {
    // The panel's controls are bound to the replaced patches: bind them to the new ones.
    surfaceEditor.reset(Math.max(0, Math.min(surfaceEditor.patch, (state.case.patches?.length ?? 1) - 1)));
    surfaceEditor.rebuild();
    state.selected = Math.min(state.selected, sourceList().length - 1);
    rebuildSourceGui();
    views.sourcePatch = surfaceEditor.patch;
    views.setSources(sourceList(), state.selected, state.view.sources);
  }
  showEditable();
  needsFit = true;
  edited(0);
});
$('domain-reset').addEventListener('click', showEditable);

// Analytic size field: an "expression" source of the case, kept in sync with the box.
// The box's source is the isotropic expression source holding the text last applied from it.
const isExprSource = (s) => s.type === 'analytic' && s.field === 'expression' && s.h2 === undefined &&
  s.alpha === undefined && s.h1 === state.exprApplied;
function setExpressionSource(text) {
  const sources = (state.case.sources ??= []);
  const i = state.exprApplied ? sources.findIndex(isExprSource) : -1;
  if (i >= 0 && !text) sources.splice(i, 1);
  else if (i >= 0) sources[i].h1 = text;
  else if (text) sources.push({ type: 'analytic', field: 'expression', h1: text });
  state.exprApplied = text || null;
}
let exprSeq = 0;
async function checkExpression(text) {
  state.view.expression = text;
  const msg = $('expr-msg');
  const seq = ++exprSeq;
  if (!text.trim()) {
    msg.hidden = true;
    state.expressionError = null;
    if (state.case && !state.surface && (state.case.sources ?? []).some(isExprSource)) { setExpressionSource(''); edited(0); }
    saveUrlSoon();
    return;
  }
  const [x0, y0, x1, y1] = domainBounds();
  const u = (x0 + x1) / 2, v = (y0 + y1) / 2;
  try {
    const { result } = await utilRunner.run('checkExpression', { text, u, v });
    if (seq !== exprSeq) return;
    msg.textContent = `ok: h(${fmtNum(u)}, ${fmtNum(v)}) = ${fmtNum(result)}`;
    msg.classList.toggle('error', !(result > 0));
    if (!(result > 0)) msg.textContent += ' — a size must be positive';
    state.expressionError = result > 0 ? null : { code: 'INVALID_ARGUMENT', message: msg.textContent };
    if (result > 0 && !state.surface) { setExpressionSource(text.trim()); edited(); }
  } catch (e) {
    if (seq !== exprSeq) return;
    msg.textContent = `${e.code}: ${e.message}`;
    msg.classList.add('error');
    state.expressionError = { code: e.code, message: e.message };
  }
  msg.hidden = false;
  saveUrlSoon();
}
$('expr').addEventListener('input', (e) => checkExpression(e.target.value));

for (const b of document.querySelectorAll('#view-mode button')) b.addEventListener('click', () => applyViewMode(b.dataset.mode));
// A link pasted into this tab (replaceState does not fire hashchange, so our own writes don't).
window.addEventListener('hashchange', () => restoreFromUrl());
// Delete / Backspace on the canvas removes the selected source.
views.canvas.addEventListener('keydown', (e) => {
  if ((e.key === 'Delete' || e.key === 'Backspace') && state.selected >= 0) {
    e.preventDefault();
    removeSource(state.selected);
  }
});

// --- adaptation mode (adapt_mode.js) ----------------------------------------------------

// The figures of an adapted mesh for the stats panel and the histograms, from its measures.
function adaptedStats(result) {
  const m = result.measures, it = result.iteration;
  const range = (a) => {
    let lo = Infinity, hi = -Infinity, sum = 0, within = 0;
    for (const x of a) {
      lo = Math.min(lo, x), hi = Math.max(hi, x), sum += x;
      if (x >= Math.SQRT1_2 && x <= Math.SQRT2) within++;
    }
    return { min: lo, max: hi, mean: sum / (a.length || 1), within: within / (a.length || 1) };
  };
  const l = range(m.edgeLength), q = range(m.quality);
  return {
    vertices: it.vertices, triangles: it.triangles, quads: 0, edges: m.edges.length / 2, inverted: 0, degenerate: 0,
    edgeLength: { min: l.min, mean: l.mean, max: l.max, fractionWithinSqrt2: l.within },
    quality: { min: q.min, mean: q.mean },
    notes: [`adapted to u(x, y): L2 error ${it.errorL2?.toExponential(2)}, L∞ ${it.errorLinf?.toExponential(2)}`],
  };
}
const adaptMode = createAdaptMode({
  runner: meshRunner,
  getMesh: () => (state.surface ? null : views.mesh),
  show(result, { iteration, of }) {
    result.measures.field = result.field;
    result.overlay = null;
    if (state.view.colorBy !== 'field') {
      state.view.colorBy = 'field';
      gui.controllersRecursive().forEach((c) => c.updateDisplay());
    }
    showResult(result);
    views.renderNow(['2d', '3d']);
    const stats = adaptedStats(result);
    state.lastStats = stats;
    renderStats(stats);
    renderHistograms(result.measures, stats);
    renderLegend();
    statusText.textContent = `adapted: iteration ${iteration} of ${of}, ${stats.vertices} vertices`;
  },
  // The adaptation's job supersedes the main lane's; the second lane's (a drag's) must not
  // draw a case mesh over the adapted one either.
  onStart() { state.adapting = true; laneRunner?.cancelAll(); status.classList.remove('err'); },
  onEnd(error) {
    state.adapting = false;
    if (error) statusText.textContent = 'adaptation failed · previous mesh shown';
    settle();
  },
  backToCase() {
    if (state.view.colorBy === 'field') state.view.colorBy = 'quality';
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
    edited(0);
  },
});

// --- test hooks -------------------------------------------------------------------------

const app = {
  state,
  views,
  meshRunner,
  /** The mesh lanes that can take a drag's input now (2 once the second one is warm). */
  readyLanes: () => readyLanes().length,
  utilRunner,
  presets: presets.map((p) => p.id),
  loadPreset,
  setCase,
  edited,
  idle,
  /** Resolves when no edit is waiting and no job runs. */
  whenIdle() { return idle() ? Promise.resolve() : new Promise((r) => completionWaiters.push(r)); },
  /** Client (page) coordinates of a source handle in the 2D view. */
  handleClientPosition(source, key) {
    const h = views.handles.find((x) => x.source === source && x.key === key);
    return h ? views.worldToClient2(h.x, h.y) : null;
  },
  selectSource,
  /** Changes display settings (keys of state.view) as the panel would. */
  setView(patch) {
    const mode = patch.view;
    Object.assign(state.view, patch);
    if (mode) applyViewMode(mode);
    restyle();
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
  },
  coverage: (which) => views.coverage(which),
  benchOrbit: (ms) => views.benchOrbit(ms),
  /** Shows a mesh that did not come from a case (e.g. a synthetic surface for a measurement). */
  showMesh(mesh) {
    const measures = { edges: uniqueEdges(mesh.triangles, mesh.quads ?? new Uint32Array(0)), edgeLength: null, quality: null, vertexH: null };
    needsFit = true;
    const stats = { vertices: mesh.params.length / 2, triangles: mesh.triangles.length / 3, quads: 0, edges: measures.edges.length / 2 };
    showResult({ mesh: { quads: new Uint32Array(0), edges: new Uint32Array(0), ...mesh }, measures, overlay: null });
    state.lastStats = stats;
    renderStats(stats);
    renderHistograms(measures, stats);
    renderLegend();
  },
  checkExpression,
  /** The adaptation mode: run({ expression, iterations }) resolves with its state. */
  adapt: adaptMode,
  loadCaseText,
  loadSvgText,
  undo,
  redo,
  edits,
};
window.anisomeshApp = app;
window.anisomeshDemo = app;  // the old name, for existing scripts

// --- start ------------------------------------------------------------------------------

fillPresetSelect();
meshRunner.ready.then((v) => {
  state.version = v;
  state.workerStartMs = Math.round(meshRunner.lastStartMs);
  $('core-version').textContent = `core ${v}`;
});
applyViewMode(state.view.view);
if (!(await restoreFromUrl())) await loadPreset(defaultPresetId);
gui.controllersRecursive().forEach((c) => c.updateDisplay());
$('expr').value = state.view.expression ?? '';
if (state.view.expression) checkExpression(state.view.expression);
applyViewMode(state.view.view);
await app.whenIdle();
state.ready = true;

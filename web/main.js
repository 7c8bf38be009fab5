// The demo page: three.js view of metric ellipses computed by the wasm core in a worker.
import * as THREE from 'three';
import GUI from 'lil-gui';

// --- worker client -----------------------------------------------------------
const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
const pending = new Map();
let nextId = 1;
worker.onmessage = ({ data }) => {
  const p = pending.get(data.id);
  if (!p) return;
  pending.delete(data.id);
  if (data.ok) p.resolve(data.result);
  else p.reject(Object.assign(new Error(data.error.message), { code: data.error.code }));
};
function call(op, args) {
  const id = nextId++;
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve, reject });
    worker.postMessage({ id, op, args });
  });
}

// --- scene -------------------------------------------------------------------
const view = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(0xf7f7f5);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, -10, 10);

const grid = new THREE.GridHelper(4, 16, 0xbbbbbb, 0xdddddd);
grid.rotation.x = Math.PI / 2;
scene.add(grid);

function ellipseObject(color, fillOpacity) {
  const group = new THREE.Group();
  const line = new THREE.LineLoop(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color }));
  const fill = new THREE.Mesh(new THREE.BufferGeometry(),
    new THREE.MeshBasicMaterial({ color, transparent: true, opacity: fillOpacity, side: THREE.DoubleSide, depthWrite: false }));
  group.add(fill, line);
  return { group, line, fill };
}
const shapes = { a: ellipseObject(0xc0392b, 0.08), b: ellipseObject(0x2163b8, 0.08), c: ellipseObject(0x1e8449, 0.3) };
for (const s of Object.values(shapes)) scene.add(s.group);

// WebGL takes Float32 positions (xyz); the core gives Float64 xy pairs.
function setEllipse(shape, xy, z) {
  const n = xy.length / 2;
  const pos = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) { pos[3 * i] = xy[2 * i]; pos[3 * i + 1] = xy[2 * i + 1]; pos[3 * i + 2] = z; }
  shape.line.geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  shape.line.geometry.computeBoundingSphere();
  // Fan triangulation from the centre for the fill.
  const fan = new Float32Array(9 * n);
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    fan.set([0, 0, z, pos[3 * i], pos[3 * i + 1], z, pos[3 * j], pos[3 * j + 1], z], 9 * i);
  }
  shape.fill.geometry.setAttribute('position', new THREE.BufferAttribute(fan, 3));
  shape.fill.geometry.computeBoundingSphere();
}

let extent = 1.2;
function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h, false);
  const aspect = w / Math.max(h, 1);
  camera.left = -extent * aspect; camera.right = extent * aspect;
  camera.top = extent; camera.bottom = -extent;
  camera.updateProjectionMatrix();
  render();
}
function render() { renderer.render(scene, camera); }
window.addEventListener('resize', resize);

// --- controls ------------------------------------------------------------------
const params = {
  m1: { alphaDeg: 20, h1: 0.25, h2: 1.0 },
  m2: { alphaDeg: 100, h1: 0.3, h2: 0.8 },
};
const gui = new GUI({ title: 'Metrics', container: document.getElementById('panel'), width: 272 });
for (const [key, label] of [['m1', 'M1'], ['m2', 'M2']]) {
  const f = gui.addFolder(label);
  f.add(params[key], 'alphaDeg', -90, 90, 1).name('alpha (deg)').onChange(update);
  f.add(params[key], 'h1', 0.01, 2, 0.01).name('h1').onChange(update);
  f.add(params[key], 'h2', 0.01, 2, 0.01).name('h2').onChange(update);
}

const errorBox = document.getElementById('error');
const state = { ready: false, updates: 0, lastError: null, intersection: null };
const fmt = (x) => x.toPrecision(4);
const toSpec = (m) => ({ alpha: (m.alphaDeg * Math.PI) / 180, h1: m.h1, h2: m.h2 });

let latest = 0;
async function update() {
  const ticket = ++latest;
  try {
    const r = await call('ellipses', { a: toSpec(params.m1), b: toSpec(params.m2) });
    if (ticket !== latest) return;  // a newer request superseded this one
    setEllipse(shapes.a, r.a, 0);
    setEllipse(shapes.b, r.b, 0.01);
    setEllipse(shapes.c, r.c, 0.02);
    extent = 1.15 * Math.max(params.m1.h1, params.m1.h2, params.m2.h1, params.m2.h2);
    document.getElementById('stat-h1').textContent = fmt(r.intersection.h1);
    document.getElementById('stat-h2').textContent = fmt(r.intersection.h2);
    document.getElementById('stat-alpha').textContent = `${fmt((r.intersection.alpha * 180) / Math.PI)}°`;
    errorBox.hidden = true;
    state.intersection = r.intersection;
    state.lastError = null;
    state.updates++;
    resize();
  } catch (e) {
    state.lastError = { code: e.code, message: e.message };
    errorBox.textContent = `${e.code}: ${e.message}`;
    errorBox.hidden = false;
  }
}

// Hooks for tests and the console.
window.anisomeshDemo = {
  state,
  params,
  update,
  call,
  // Fraction of canvas pixels that differ from the background colour.
  canvasCoverage() {
    const src = renderer.domElement;
    const c = document.createElement('canvas');
    c.width = src.width; c.height = src.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(src, 0, 0);
    const data = ctx.getImageData(0, 0, c.width, c.height).data;
    let differing = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - 0xf7) + Math.abs(data[i + 1] - 0xf7) + Math.abs(data[i + 2] - 0xf5) > 24) differing++;
    }
    return differing / (c.width * c.height);
  },
};

call('version').then((v) => {
  document.getElementById('core-version').textContent = v;
  state.version = v;
});
resize();
await update();
state.ready = true;

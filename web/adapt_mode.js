// The page's adaptation mode: the current planar mesh adapted to a function u(x, y) typed by
// the user (the package's adapt(): Hessian recovery, L^p or error-level metric, remeshing).
// Each iteration is one worker job, so every mesh is drawn as it arrives, coloured by the
// field, and its N and interpolation errors go into a table and a log-log plot of error
// against N. An edit of the case supersedes the running job and ends the loop.
import { CancelledError } from './jobs.js';
import { css, fieldColor } from './colors.js';

const $ = (id) => document.getElementById(id);

/**
 * deps: runner (JobRunner, superseding), getMesh() (the planar mesh on screen or null),
 * show(result, figures) (puts an adapted mesh on screen), onStart(), onEnd(error|null),
 * backToCase() (remeshes the case).
 */
export function createAdaptMode(deps) {
  const state = { running: false, iterations: [], expression: null, error: null, runs: 0 };
  const msg = $('error-adapt');

  function options() {
    const value = Number($('adapt-value').value);
    const o = { norm: $('adapt-norm').value, shape: $('adapt-shape').value };
    if ($('adapt-target').value === 'err') o.err = value, o.relative = true;
    else o.nv = Math.round(value);
    const hmax = Number($('adapt-hmax').value);
    if (hmax > 0) o.hmax = hmax;
    return o;
  }

  function showError(text) {
    state.error = text;
    msg.textContent = text ?? '';
    msg.hidden = !text;
  }

  const fmt = (x) => (x === undefined ? '–' : Number(x).toExponential(2));
  function renderTable() {
    const rows = state.iterations.map((it, k) => `<tr><td>${k + 1}</td><td>${it.vertices}</td><td>${it.triangles}</td>` +
      `<td>${fmt(it.errorL2)}</td><td>${fmt(it.errorLinf)}</td></tr>`);
    $('adapt-table').innerHTML = state.iterations.length
      ? `<tr><th>it.</th><th>N</th><th>triangles</th><th>L2 error</th><th>L∞ error</th></tr>${rows.join('')}` : '';
  }

  // Log-log plot of the L2 and L-infinity errors of the P1 interpolant against N.
  function renderPlot() {
    const canvas = $('adapt-plot');
    const dpr = window.devicePixelRatio || 1;
    const w = canvas.clientWidth || 280, h = canvas.clientHeight || 120;
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
    const g = canvas.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    const pts = state.iterations.filter((it) => it.errorL2 > 0 && it.errorLinf > 0);
    g.fillStyle = '#555';
    g.font = '10px sans-serif';
    g.fillText('error against N (log-log)', 4, 11);
    if (!pts.length) return;
    const xs = pts.map((p) => Math.log10(p.vertices));
    const ys = pts.flatMap((p) => [Math.log10(p.errorL2), Math.log10(p.errorLinf)]);
    const x0 = Math.min(...xs) - 0.1, x1 = Math.max(...xs) + 0.1, y0 = Math.min(...ys) - 0.1, y1 = Math.max(...ys) + 0.1;
    const px = (x) => 30 + ((x - x0) / (x1 - x0)) * (w - 40), py = (y) => h - 16 - ((y - y0) / (y1 - y0)) * (h - 32);
    g.strokeStyle = '#bbb';
    g.strokeRect(30, 16, w - 40, h - 32);
    g.fillText(`N ${Math.round(10 ** x0)}…${Math.round(10 ** x1)}`, 32, h - 4);
    for (const [key, color] of [['errorL2', fieldColor(0)], ['errorLinf', fieldColor(1)]]) {
      g.strokeStyle = g.fillStyle = css(color);
      g.beginPath();
      pts.forEach((p, i) => {
        const x = px(Math.log10(p.vertices)), y = py(Math.log10(p[key]));
        if (i) g.lineTo(x, y);
        else g.moveTo(x, y);
      });
      g.stroke();
      for (const p of pts) g.fillRect(px(Math.log10(p.vertices)) - 2, py(Math.log10(p[key])) - 2, 4, 4);
    }
    g.fillStyle = css(fieldColor(0));
    g.fillText('L2', w - 44, 28);
    g.fillStyle = css(fieldColor(1));
    g.fillText('L∞', w - 24, 28);
  }

  /** Runs the loop from the mesh on screen; resolves when it ends (done, failed or superseded). */
  async function run({ expression = $('adapt-expr').value, iterations = Number($('adapt-iterations').value) } = {}) {
    if (state.running) return state;
    let mesh = deps.getMesh();
    showError(null);
    if (!mesh || mesh.dimension !== 2) {
      showError('adaptation needs a planar mesh: load a planar preset first');
      return state;
    }
    $('adapt-expr').value = expression;
    state.running = true;
    state.expression = expression;
    state.iterations = [];
    state.runs++;
    renderTable();
    renderPlot();
    deps.onStart();
    let error = null;
    try {
      for (let k = 0; k < Math.max(1, Math.min(20, Math.round(iterations) || 1)); k++) {
        const { result } = await deps.runner.run('adapt', { mesh, expression, options: options() });
        mesh = result.mesh;
        state.iterations.push(result.iteration);
        deps.show(result, { iteration: k + 1, of: iterations });
        renderTable();
        renderPlot();
      }
    } catch (e) {
      if (!(e instanceof CancelledError)) {
        error = { code: e.code ?? 'INTERNAL', message: e.message };
        showError(`${error.code}: ${error.message}`);
      }
    } finally {
      state.running = false;
      deps.onEnd(error);
    }
    return state;
  }

  $('adapt-run').addEventListener('click', () => run());
  $('adapt-reset').addEventListener('click', () => {
    state.iterations = [];
    renderTable();
    renderPlot();
    deps.backToCase();
  });
  return { state, run };
}

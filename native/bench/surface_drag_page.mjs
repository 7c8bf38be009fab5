#!/usr/bin/env node
// Issue #12's figure, measured on the page: drags of a radial source on "Surface p2 with
// holes" (examples/surface/surface_p2_holes.json, ~5.8k triangles with the source) and the
// same case refined (chord tolerance 0.0025, hmax 0.3: ~53k), in headless Chromium
// (tests/browser/launch.mjs). Per drag: the drag's last edit -> its mesh drawn (the app's
// dragInputToMeshMs: "total"), the worker's part (the core call, coreMs, and the worker's
// whole job, workerMs), the result's way to the page (toPageMs) and the main thread's draw
// (geometry + render), whether the release cancelled a stale job (the spare worker then
// meshes), the CPU ms of the GPU process over the drag (with software WebGL it rasterizes and
// composites every frame on the cores the mesher uses: ~25 ms per WebGL frame here), and the
// CPU ms of Chromium's renderer over the drag (all threads: the workers,
// the spare's warm-up, the page's drawing). Also a plain edit of the source (no drag: a warm worker, no
// cancellation). And "idle": the core's run with nothing else on the page (jobs posted straight to
// the mesh worker: no toolbar, no draw), against which the drags' core runs show the
// contention. Prints a table of medians (no timed assertions; a measurement).
//
// Usage: node native/bench/surface_drag_page.mjs [--drags N] [--only small|refined] [--no-isolation] [--lanes 1|2] [--threads 1|2]
//   CHROMIUM_EXTRA_ARGS="--disable-gpu-compositing" adds Chromium flags (e.g. that one composites
//   the page in software instead of through SwiftShader, as a machine with a GPU would not pay).
//   --lanes 1: one mesh worker for drags (the latest input waits for a stale job or the release).
//   --no-isolation: the page without COOP / COEP (?isolation=off): stale jobs are cancelled by
//   terminating the worker (the spare takes over) instead of inside the worker.
import { chromium } from 'playwright-core';
import { chromiumCpuMs } from './chromium_cpu.mjs';
import { chromiumArgs, dragSourceOnce, openSurfaceDragPage, settle } from '../../tests/browser/launch.mjs';
import { refinedP2Metric } from '../../tests/browser/fixtures.mjs';
import { startServer } from '../../web/serve.mjs';

const args = process.argv.slice(2);
const opt = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const drags = Number(opt('--drags', 11));
const query = [process.argv.includes('--no-isolation') ? 'isolation=off' : null, args.includes('--lanes') ? `lanes=${opt('--lanes')}` : null,
  args.includes('--threads') ? `threads=${opt('--threads')}` : null].filter(Boolean);
const pageQuery = query.length ? `?${query.join('&')}` : '';
const only = opt('--only', null);
const median = (a) => (a.length ? [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)] : NaN);

// CPU ns of Chromium's processes of a type (all threads; a terminated worker's CPU stays counted).
const workerCpuNs = (type = 'renderer') => chromiumCpuMs(type) * 1e6;

const cases = [
  ['small', 'p2 with holes + radial source', null],
  ['refined', 'p2 refined (chord 0.0025, hmax 0.3) + radial source', refinedP2Metric],
].filter(([id]) => !only || only === id);

// CHROMIUM_JS_FLAGS="--no-wasm-dynamic-tiering" passes V8 flags (e.g. to see what tier-up costs).
const { server, url } = await startServer({ port: 0 });
const jsFlags = process.env.CHROMIUM_JS_FLAGS;
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', headless: true,
  args: [...chromiumArgs, ...(jsFlags ? [`--js-flags=${jsFlags}`] : []), ...(process.env.CHROMIUM_EXTRA_ARGS?.split(' ').filter(Boolean) ?? [])],
});
const env = { browser, url, close: async () => { await browser.close(); await new Promise((r) => server.close(r)); } };
const rows = [];
try {
  for (const [, label, edit] of cases) {
    const { page, errors } = await openSurfaceDragPage(env.browser, env.url + pageQuery, edit);
    await page.evaluate(() => new Promise((r) => setTimeout(r, 500)));  // the spare's warm-up
    // Plain edits: the source moved from the panel (one job on a warm worker).
    const plain = [];
    for (let k = 0; k < 5; k++) {
      const n0 = workerCpuNs(), g0 = workerCpuNs('gpu-process');
      await settle(page, (x) => {
        const a = window.anisomeshApp;
        a.state.case.patches[0].sources[0].center = [x, 0.05];
        a.edited(0);
      }, 0.05 * (k + 1));
      const r = await page.evaluate(() => ({ b: window.anisomeshApp.state.breakdowns.at(-1), job: window.anisomeshApp.state.lastJob }));
      plain.push({ ...r.b, workerMs: r.job.workerMs, cpu: (workerCpuNs() - n0) / 1e6, gpu: (workerCpuNs('gpu-process') - g0) / 1e6 });
    }
    // The core alone on the page: mesh jobs posted straight to the mesh worker (the runner
    // sees no job: no busy toolbar, no result drawn, no frame), as a drag's are, once the
    // spare's and the second lane's warm-up runs are over. What the drags' core runs take
    // beyond this is contention (frames, the other lane, the page). (They replace the run the
    // worker keeps for its report: the drags that follow make their own.)
    await page.evaluate(() => new Promise((r) => setTimeout(r, 2000)));
    const idle = await page.evaluate(async (n) => {
      const app = window.anisomeshApp, w = app.meshRunner.worker, out = [];
      for (let k = 0; k < n; k++) {
        const c = structuredClone(app.state.case);
        const s = c.patches[0].sources[0];
        s.center = [s.center[0] + 0.01 * (k % 7), s.center[1]];
        const id = 1e9 + k;  // above every runner id: never cancelled, matched by no pending job
        const r = await new Promise((res) => {
          const h = ({ data }) => { if (data.id === id && data.type === 'result') { w.removeEventListener('message', h); res(data); } };
          w.addEventListener('message', h);
          w.postMessage({ type: 'job', id, op: 'mesh', args: { case: c, surface: true, dragging: true, progress: false }, postedAt: performance.timeOrigin + performance.now() });
        });
        if (!r.ok) throw new Error(r.error.message);
        out.push(r.marks.coreEnd - r.marks.coreStart);
      }
      return out.slice(10);  // after the tier-up
    }, 30);
    const samples = [];
    for (let rep = 0; rep < drags; rep++) {
      const before = await page.evaluate(() => window.anisomeshApp.meshRunner.cancellations);
      const n0 = workerCpuNs(), g0 = workerCpuNs('gpu-process');
      await dragSourceOnce(page, rep);
      const r = await page.evaluate(() => {
        const a = window.anisomeshApp, s = a.state;
        return { total: s.dragInputToMeshMs, up: s.dragToMeshMs, b: s.breakdowns.filter((x) => x.drag).at(-1) ?? null, job: s.lastJob, cancellations: a.meshRunner.cancellations, tris: a.views.mesh.triangles.length / 3, threads: a.meshRunner.threads, drawn: s.meshesDrawn };
      });
      await page.evaluate(() => new Promise((res) => setTimeout(res, 300)));
      samples.push({ ...r, cancelled: r.cancellations - before, cpu: (workerCpuNs() - n0) / 1e6, gpu: (workerCpuNs('gpu-process') - g0) / 1e6 });
    }
    if (errors.length) console.log('page errors:', errors);
    rows.push({ label, plain, samples, idle });
    await page.close();
  }
} finally {
  await env.close();
}

const f = (x) => (Number.isFinite(x) ? x.toFixed(0) : '-');
console.log(`median ms (drags: ${drags} each; plain edits: 5). total = the last edit -> its mesh drawn; worker = the core call in the worker (coreMs);`);
console.log('job = the worker\'s whole job; page = result to page + geometry + render; cpu = Chromium renderer CPU over the drag (all threads: workers, the spare\'s warm-up, drawing);');
console.log('gpu = the GPU process\'s CPU over the drag (software WebGL: rasterizing and compositing the frames, on the same cores as the mesher)');
console.log('case'.padEnd(52), 'kind'.padEnd(6), 'triangles', 'total', 'worker', '  job', ' page', '  cpu', '  gpu', 'cancelled');
for (const { label, plain, samples, idle } of rows) {
  const m = (list, key) => median(list.map((s) => (typeof key === 'function' ? key(s) : s[key])).filter((x) => Number.isFinite(x)));
  const page = (b) => (b ? b.toPageMs + b.geometryMs + b.renderMs : NaN);
  console.log(label.padEnd(52), 'drag'.padEnd(6), String(samples.at(-1).tris).padStart(9), f(m(samples, 'total')).padStart(5),
    f(m(samples, (s) => s.b?.coreMs)).padStart(6), f(m(samples, (s) => s.job?.workerMs)).padStart(5), f(m(samples, (s) => page(s.b))).padStart(5),
    f(m(samples, 'cpu')).padStart(5), f(m(samples, 'gpu')).padStart(5), `${samples.filter((s) => s.cancelled > 0).length}/${samples.length}`.padStart(9));
  console.log(''.padEnd(52), 'edit'.padEnd(6), String(plain.at(-1).triangles).padStart(9), f(m(plain, 'inputToDrawnMs')).padStart(5),
    f(m(plain, 'coreMs')).padStart(6), f(m(plain, 'workerMs')).padStart(5), f(m(plain, page)).padStart(5), f(m(plain, 'cpu')).padStart(5), f(m(plain, 'gpu')).padStart(5), '-'.padStart(9));
  console.log(''.padEnd(52), 'idle'.padEnd(6), '-'.padStart(9), '-'.padStart(5), f(median(idle)).padStart(6), '    -', '    -', '    -', '    -', '-'.padStart(9),
    ` (core alone on the page, ${idle.length} runs: ${Math.round(Math.min(...idle))}-${Math.round(Math.max(...idle))} ms)`);
  const parts = ['inputToPostMs', 'postToStartMs', 'coreRunMs', 'coreOutputMs', 'coreMeasuresMs', 'toPageMs', 'geometryMs', 'renderMs'];
  console.log('  drag breakdown (median ms):', parts.map((k) => `${k.replace(/Ms$/, '')} ${m(samples, (s) => s.b?.[k]).toFixed(1)}`).join(', '));
  console.log('  lanes that drew:', samples.map((s) => s.b?.lane ?? '-').join(' '));
  console.log('  core threads in the mesh worker:', samples.at(-1).threads ?? '-');
  console.log(`  meshes drawn over the drags: ${samples.at(-1).drawn - samples[0].drawn + 1}`);
  console.log('  drags, total:', samples.map((s) => s.total).join(' '), ' worker:', samples.map((s) => f(s.b?.coreMs)).join(' '));
}

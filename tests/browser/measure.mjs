// Measurements for the report (not a test: no timed assertions) and the README screenshots.
//   node tests/browser/measure.mjs [--no-screenshots]
// Prints: pointer-up -> new mesh drawn for a ~50k-triangle case (DRAGS drags, default 12)
// with where the time went (the app's breakdown: see draw() in web/app.js), and the frame
// rate while orbiting a ~200k-triangle mesh in the 3D view (headless Chromium, software WebGL).
// ONLY=drag, ONLY=orbit, ONLY=surface or ONLY=shots runs one part; SYNC=1 makes "drawn" wait for the GPU.
// ONLY=surface: drags of a radial source on "Surface p2 with holes", as is (about 2,845
// triangles + the source's refinement) and refined to about 50k triangles.
import { dragSourceOnce, launch, openPage, openSurfaceDragPage, settle } from './launch.mjs';
import { refinedP2Metric, sphereMesh } from './fixtures.mjs';
import { fileURLToPath } from 'node:url';
import { stat } from 'node:fs/promises';

const only = process.env.ONLY ?? null;
const shots = !process.argv.includes('--no-screenshots') && (!only || only === 'shots');
const out = fileURLToPath(new URL('../../web/screenshots/', import.meta.url));
const env = await launch();
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];

try {
  if (!only || only === 'drag') {
  // --- 1. drag -> mesh for ~50k triangles ---------------------------------------------
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('point-source-fine'));
  await settle(page, () => {
    const a = window.anisomeshApp;
    a.state.case.sources[0].h0 = 0.0006;
    a.state.case.controlSpace.hmin = 0.0006;
    a.state.case.controlSpace.hmax = 0.0105;
    a.edited(0);
  });
  const base = await page.evaluate(() => ({ tris: window.anisomeshApp.state.lastStats.triangles, job: window.anisomeshApp.state.lastJob }));
  console.log(`case: preset point-source-fine with h0 = hmin = 0.0006, hmax = 0.0105: ${base.tris} triangles; job ${JSON.stringify(base.job)}`);
  const drags = Number(process.env.DRAGS ?? 12);
  // SYNC=1: the app's draw waits until the GPU has finished the frame (a 1-pixel read
  // back), so "drawn" means pixels done rather than commands issued.
  if (process.env.SYNC) await page.evaluate(() => { window.anisomeshApp.state.syncDraw = true; });
  // The page's own record of the last pointer move and of the release (any app version).
  await page.evaluate(() => {
    const c = document.querySelector('#view canvas');
    c.addEventListener('pointermove', () => { window.lastMoveAt = performance.now(); }, { capture: true });
    c.addEventListener('pointerup', () => { window.upAt = performance.now(); }, { capture: true });
  });
  const moveSamples = [];
  const samples = [], inputSamples = [], breakdowns = [];
  for (let rep = 0; rep < drags; rep++) {
    await dragSourceOnce(page, rep);
    const r = await page.evaluate(() => {
      const s = window.anisomeshApp.state;
      const b = (s.breakdowns ?? []).filter((x) => x.drag).at(-1) ?? null;
      const fresh = b && b !== window.lastDragBreakdown;
      window.lastDragBreakdown = b;
      return { ms: s.dragToMeshMs, inputMs: s.dragInputToMeshMs, gap: window.upAt - window.lastMoveAt, job: s.lastJob, tris: s.lastStats.triangles, b: fresh ? b : null };
    });
    samples.push(r.ms);
    // Last move -> drawn: the move-to-release gap plus release -> drawn (0 when the mesh of
    // the last move was drawn before the release: then the app's breakdown has the figure).
    moveSamples.push(r.ms > 0 || r.inputMs == null ? Math.round(r.gap + r.ms) : r.inputMs);
    if (r.inputMs != null) inputSamples.push(r.inputMs);
    if (r.b) breakdowns.push(r.b);
    console.log(`  drag ${rep + 1}: pointer up -> mesh drawn ${r.ms} ms (${r.tris} triangles; core ${r.job.meshMs} ms, worker ${r.job.workerMs} ms, round trip ${r.job.totalMs} ms, draw ${r.job.drawMs} ms)` +
      (r.b ? `\n    breakdown ${JSON.stringify(r.b)}` : ''));
    await page.evaluate(() => new Promise((res) => setTimeout(res, 150)));
  }
  console.log(`RESULT drag->mesh drawn (~${base.tris} triangles): median ${median(samples)} ms of ${samples.length} drags: ${samples.join(', ')}`);
  console.log(`RESULT last pointer move -> mesh drawn (~${base.tris} triangles): median ${median(moveSamples)} ms of ${moveSamples.length} drags: ${moveSamples.join(', ')}`);
  if (inputSamples.length) console.log(`RESULT last edit of the case -> mesh drawn (app's own figure): median ${median(inputSamples)} ms of ${inputSamples.join(', ')}`);
  if (breakdowns.length) {
    // Median of each stage over the drags (the stages of one drag add up to its total; medians need not).
    const keys = Object.keys(breakdowns[0]).filter((k) => typeof breakdowns[0][k] === 'number');
    console.log(`RESULT breakdown, median of ${breakdowns.length} drags (ms):`);
    for (const k of keys) console.log(`  ${k.padEnd(20)} ${median(breakdowns.map((b) => b[k] ?? 0))}`);
  }
  const restarts = await page.evaluate(() => window.anisomeshApp.state.workerRestartMs);
  console.log(`RESULT worker restart after cancel (precompiled wasm module): median ${median(restarts)} ms of ${restarts.length}`);
  if (errors.length) console.log('page errors:', errors);
  await page.close();

  // --- 1b. worker replacement cost with and without the precompiled module ------------
  for (const q of ['', '?spare=0', '?spare=0&precompile=0']) {
    const { page: pc } = await openPage(env.browser, env.url.replace(/\/web\/$/, '/web/index.html') + q);
    await settle(pc, () => window.anisomeshApp.loadPreset('holes-off'));
    const ms = await pc.evaluate(async () => {
      const a = window.anisomeshApp;
      for (let k = 0; k < 5; k++) {
        a.state.case.sources[0].metric.h1 = 0.05 + 0.001 * k;
        a.edited(0);
        await new Promise((r) => setTimeout(r, 30));
        a.state.case.sources[0].metric.h1 = 0.06 + 0.001 * k;
        a.edited(0);
        await a.whenIdle();
      }
      return a.state.workerRestartMs;
    });
    const how = { '': 'spare worker (default)', '?spare=0': 'no spare, precompiled module', '?spare=0&precompile=0': 'no spare, no precompiled module' }[q];
    console.log(`RESULT worker restart after a cancel, ${how}: median ${median(ms)} ms of ${ms.join(', ')}`);
    await pc.close();
  }

  }
  if (!only || only === 'surface') {
  // --- 1c. drag a source on a surface (p2 with holes) -----------------------------------
  for (const [label, edit] of [
    ['p2 with holes, a radial source', null],
    ['p2 with holes refined (chord tolerance 0.0025, hmax 0.3), a radial source', refinedP2Metric],
  ]) {
    const { page, errors } = await openSurfaceDragPage(env.browser, env.url, edit);
    const base = await page.evaluate(() => ({ tris: window.anisomeshApp.views.mesh.triangles.length / 3, job: window.anisomeshApp.state.lastJob }));
    const drags = Number(process.env.DRAGS ?? 12);
    const samples = [], breakdowns = [];
    for (let rep = 0; rep < drags; rep++) {
      await dragSourceOnce(page, rep);
      const r = await page.evaluate(() => {
        const s = window.anisomeshApp.state;
        return { ms: s.dragInputToMeshMs, tris: window.anisomeshApp.views.mesh.triangles.length / 3, b: (s.breakdowns ?? []).filter((x) => x.drag).at(-1) ?? null };
      });
      samples.push(r.ms);
      if (r.b) breakdowns.push(r.b);
      await page.evaluate(() => new Promise((res) => setTimeout(res, 150)));
    }
    console.log(`RESULT surface drag, ${label} (~${base.tris} triangles): last edit -> mesh drawn median ${median(samples)} ms of ${samples.length}: ${samples.join(', ')}`);
    if (breakdowns.length) {
      const keys = Object.keys(breakdowns[0]).filter((k) => typeof breakdowns[0][k] === 'number');
      console.log(`  breakdown, median of ${breakdowns.length} drags (ms): ` + keys.map((k) => `${k} ${median(breakdowns.map((b) => b[k] ?? 0))}`).join(', '));
    }
    if (errors.length) console.log('page errors:', errors);
    await page.close();
  }
  }
  if (!only || only === 'orbit') {
  // --- 2. orbit a ~200k-triangle mesh -------------------------------------------------
  const { page: p2, errors: e2 } = await openPage(env.browser, env.url);
  await settle(p2, () => window.anisomeshApp.loadPreset('point-source-fine'));
  await settle(p2, () => {
    const a = window.anisomeshApp;
    a.state.case.sources[0].h0 = 0.0003;
    a.state.case.controlSpace.hmin = 0.0003;
    a.state.case.controlSpace.hmax = 0.0048;
    a.state.view.lift = 0.5;
    a.edited(0);
  });
  // Two settings: the default (edge lines hidden while the camera moves, above 60k edges)
  // and the edges drawn. A warm-up orbit first (the first seconds after a mesh run slower:
  // the worker's report, garbage collection), then the settings alternately, twice; the
  // mean of the two.
  const orbit = async () => p2.evaluate(async () => {
    const a = window.anisomeshApp, v = a.views;
    await a.whenIdle();
    const out = { byDefault: 0, withEdges: 0 };
    await v.benchOrbit(2000);
    for (let k = 0; k < 2; k++) {
      out.byDefault += (await v.benchOrbit(3000)) / 2;
      v.hideEdgesAbove = Infinity;
      out.withEdges += (await v.benchOrbit(3000)) / 2;
      v.hideEdgesAbove = 60000;
    }
    return out;
  });
  const fps = (o) => `${o.byDefault.toFixed(1)} fps by default (edge lines hidden while moving), ${o.withEdges.toFixed(1)} fps with the edges drawn`;
  const planarInfo = await p2.evaluate(() => {
    const a = window.anisomeshApp;
    a.views.setStyle({ colorBy: 'quality', edges: 'length', lift: 0.5 });
    a.views.setMode('3d');
    a.views.fit3D();
    return { tris: a.state.lastStats.triangles, edges: a.state.lastStats.edges, job: a.state.lastJob };
  });
  const planar = await orbit();
  console.log(`RESULT orbit planar mesh lifted in 3D, ${planarInfo.tris} triangles, ${planarInfo.edges} edges (meshing ${planarInfo.job.meshMs} ms): ${fps(planar)}`);
  const sphereTris = await p2.evaluate(sphereMesh, 200000);
  await p2.evaluate(() => { const v = window.anisomeshApp.views; v.setMode('3d'); v.fit3D(); });
  const sphere = await orbit();
  console.log(`RESULT orbit synthetic sphere (dimension 3), ${sphereTris} triangles: ${fps(sphere)}`);
  if (e2.length) console.log('page errors:', e2);
  await p2.close();

  }
  // --- 3. screenshots -----------------------------------------------------------------
  if (shots) {
    const { page: p3 } = await openPage(env.browser, env.url);
    await settle(p3, () => window.anisomeshApp.loadPreset('holes-dr2'));
    await p3.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await p3.screenshot({ path: `${out}app-holes-dr2.png` });
    await settle(p3, () => window.anisomeshApp.loadPreset('shear-layer'));
    await p3.evaluate(() => {
      const a = window.anisomeshApp;
      a.setView({ controlSpace: true, edges: 'plain', lift: 0.6 });
    });
    await settle(p3);  // the overlay is inspected when it is turned on
    await p3.evaluate(() => window.anisomeshApp.views.fit3D());
    await p3.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await p3.screenshot({ path: `${out}app-shear-layer-control-space.png` });
    await settle(p3, () => window.anisomeshApp.loadPreset('boundary-layer'));
    await p3.evaluate(() => {
      const a = window.anisomeshApp;
      a.setView({ controlSpace: false, edges: 'length', lift: 0 });
      a.state.case.options.quads = true;
      a.edited(0);
    });
    await settle(p3);
    await p3.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await p3.screenshot({ path: `${out}app-boundary-layer-quads.png` });
    // A long run in progress: the toolbar's stage, bar and percentage.
    await settle(p3, () => window.anisomeshApp.loadPreset('point-source-fine'));
    await p3.evaluate(() => {
      const a = window.anisomeshApp;
      a.state.case.options.quads = false;
      a.setView({ edges: 'length', lift: 0 });
      a.state.case.sources[0].h0 = 0.0002;
      a.state.case.controlSpace.hmin = 0.0002;
      a.state.case.controlSpace.hmax = 0.003;
      a.edited(0);
    });
    await p3.waitForFunction(() => {
      const p = window.anisomeshApp.state.progress;
      return p?.stage === 'inserting points' && p.fraction > 0.25;
    }, null, { timeout: 60000, polling: 20 });
    await p3.screenshot({ path: `${out}app-progress.png`, clip: { x: 0, y: 0, width: 1280, height: 120 } });
    await settle(p3);
    for (const f of ['app-holes-dr2.png', 'app-shear-layer-control-space.png', 'app-boundary-layer-quads.png', 'app-progress.png']) {
      console.log(`screenshot web/screenshots/${f}: ${((await stat(out + f)).size / 1024).toFixed(0)} KB`);
    }
    await p3.close();
  }
  // --- 4. surface screenshots (ONLY=surfshots, or with the others) -----------------------
  if (shots || only === 'surfshots') {
    const { page: p4 } = await openPage(env.browser, env.url);
    const frame = () => p4.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    // The surface editor: a height field typed as an expression.
    await settle(p4, () => window.anisomeshApp.loadPreset('new-heightfield'));
    await settle(p4, () => {
      const a = window.anisomeshApp;
      a.state.case.patches[0].surface.z = '0.35*exp(-3*((u-1.3)^2+(v-0.8)^2)) - 0.2*sin(2*u)*cos(3*v)';
      a.state.case.patches[0].holes = [[{ type: 'circle', center: [0.6, 1.4], radius: 0.25 }]];
      a.setView({ colorBy: 'quality', edges: 'plain' });
      a.edited(0);
    });
    await frame();
    await p4.screenshot({ path: `${out}app-surface-editor.png` });
    // A source on a surface: p2 with a radial source (its handles in both views).
    await settle(p4, () => window.anisomeshApp.loadPreset('p2-holes'));
    await settle(p4, () => {
      const a = window.anisomeshApp;
      a.state.case.patches[0].sources = [{ type: 'radial', center: [0.5, -1], metric: { alpha: 0, h1: 0.08, h2: 0.08 }, radius: 1.8 }];
      a.selectSource(0);
      a.edited(0);
    });
    await frame();
    await p4.screenshot({ path: `${out}app-surface-source.png` });
    // The per-patch control spaces of figs. 11-13, side by side in (u, v) and on the surface.
    await settle(p4, () => window.anisomeshApp.loadPreset('two-patch-c'));
    await settle(p4, () => window.anisomeshApp.setView({ controlSpace: true, edges: 'plain' }));
    await frame();
    await p4.screenshot({ path: `${out}app-surface-control-space.png` });
    for (const f of ['app-surface-editor.png', 'app-surface-source.png', 'app-surface-control-space.png']) {
      console.log(`screenshot web/screenshots/${f}: ${((await stat(out + f)).size / 1024).toFixed(0)} KB`);
    }
    await p4.close();
  }
} finally {
  await env.close();
}

// The browser app in headless Chromium: presets mesh and render, sources drag on the
// canvas, bad input gives inline errors, the state lives in the URL, cancellation.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { launch, openPage, settle } from './launch.mjs';
import { sphereMesh } from './fixtures.mjs';

let env;
before(async () => { env = await launch(); });
after(async () => { await env?.close(); });

const statValue = (page, key) => page.locator(`#stats dd[data-key="${key}"]`).textContent();

test('every preset meshes, renders a non-blank canvas and shows its counts', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  const ids = await page.evaluate(() => window.anisomeshApp.presets);
  assert.ok(ids.length >= 6, `presets: ${ids}`);
  for (const id of ids) {
    await settle(page, (p) => window.anisomeshApp.loadPreset(p), id);
    const r = await page.evaluate(() => {
      const a = window.anisomeshApp;
      const m = a.views.mesh;
      return {
        error: a.state.lastError,
        preset: a.state.presetId,
        stats: a.state.lastStats,
        drawn: { vertices: m.params.length / 2, triangles: m.triangles.length / 3, quads: m.quads.length / 4 },
        surface: a.views.mesh.dimension === 3,
        meanQ: a.state.lastMeasures.quality
          ? a.state.lastMeasures.quality.reduce((s, q) => s + q, 0) / a.state.lastMeasures.quality.length
          : null,
        cov2: a.coverage('2d'),
        cov3: a.coverage('3d'),
      };
    });
    assert.equal(r.error, null, `${id}: ${JSON.stringify(r.error)}`);
    assert.equal(r.preset, id);
    assert.ok(r.stats.triangles > 100, `${id}: ${r.stats.triangles} triangles`);
    assert.deepEqual(r.drawn, { vertices: r.stats.vertices, triangles: r.stats.triangles, quads: r.stats.quads }, id);
    if (r.surface) {
      // Surface cases report their quality measured in 3D.
      assert.ok(r.stats.quality.mean > 0.8, `${id}: 3D mean Q ${r.stats.quality.mean}`);
    } else {
      // The worker's per-element qualities (the colours, the histogram) match the core's report.
      assert.ok(Math.abs(r.meanQ - r.stats.quality.mean) < 1e-3, `${id}: mean Q ${r.meanQ} vs ${r.stats.quality.mean}`);
    }
    assert.ok(r.cov2 > 0.05, `${id}: 2D view coverage ${r.cov2}`);
    assert.ok(r.cov3 > 0.05, `${id}: 3D view coverage ${r.cov3}`);
    assert.equal(await statValue(page, 'triangles'), String(r.stats.triangles), id);
    assert.equal(await statValue(page, 'vertices'), String(r.stats.vertices), id);
  }
  assert.deepEqual(errors, []);
  await page.close();
});

test('dragging a radial source with the mouse moves it and remeshes', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('holes-off'));
  const before = await page.evaluate(() => {
    const a = window.anisomeshApp;
    return { center: a.state.case.sources[0].center, jobs: a.state.jobsDone, vertices: Array.from(a.views.mesh.params.slice(0, 4000)), n: a.views.mesh.params.length };
  });
  const h = await page.evaluate(() => window.anisomeshApp.handleClientPosition(0, 'center'));
  assert.ok(h, 'handle of source 0 is on screen');
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  for (let k = 1; k <= 8; k++) await page.mouse.move(h.x - 8 * k, h.y + 4 * k);
  await page.mouse.up();
  await page.waitForFunction(() => window.anisomeshApp.state.dragToMeshMs !== null && window.anisomeshApp.idle(), null, { timeout: 30000 });
  const after = await page.evaluate(() => {
    const a = window.anisomeshApp;
    return { center: a.state.case.sources[0].center, jobs: a.state.jobsDone, vertices: Array.from(a.views.mesh.params.slice(0, 4000)), n: a.views.mesh.params.length, error: a.state.lastError, selected: a.state.selected };
  });
  assert.equal(after.error, null);
  assert.equal(after.selected, 0);
  assert.ok(after.center[0] < before.center[0] - 0.3 && after.center[1] < before.center[1] - 0.1, `moved: ${before.center} -> ${after.center}`);
  assert.ok(after.jobs > before.jobs);
  assert.ok(after.n !== before.n || after.vertices.some((v, i) => v !== before.vertices[i]), 'the mesh changed');
  // The panel follows the handle.
  const cx = await page.locator('#gui .lil-controller', { hasText: 'center x' }).locator('input').inputValue();
  assert.ok(Math.abs(Number(cx) - after.center[0]) < 1e-3, `panel shows ${cx}, source at ${after.center[0]}`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('bad input shows an inline error next to its control, keeps the mesh, and recovers', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('holes-off'));
  const plain = await page.evaluate(() => window.anisomeshApp.state.lastStats.triangles);

  // 1. An expression that does not parse, then a valid one, which meshes again with it.
  await page.locator('#expr-box summary').click();
  await page.locator('#expr').fill('0.1 + sin(x');
  await page.waitForFunction(() => !document.getElementById('expr-msg').hidden && /PARSE_ERROR/.test(document.getElementById('expr-msg').textContent));
  assert.match(await page.locator('#expr-msg').textContent(), /column/);
  await page.locator('#expr').fill('0.15 + 0.05*sin(x)');
  await page.waitForFunction(() => /^ok: h\(/.test(document.getElementById('expr-msg').textContent));
  await settle(page);
  const meshBefore = await page.evaluate(() => window.anisomeshApp.state.lastStats.triangles);
  assert.ok(meshBefore > plain, `the size field refines the mesh: ${plain} -> ${meshBefore} triangles`);

  // 2. A source with zero radius: error under the radius field, previous mesh kept.
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.sources[1].radius = 0; a.edited(0); });
  let r = await page.evaluate(() => ({ err: window.anisomeshApp.state.lastError, tris: window.anisomeshApp.views.mesh.triangles.length / 3 }));
  assert.equal(r.err.target, 'sources[1].radius');
  assert.equal(r.tris, meshBefore, 'the previous mesh stays');
  const radiusRow = page.locator('#gui .lil-controller.has-error', { hasText: 'radius' });
  await radiusRow.waitFor();
  assert.match(await page.locator('#gui .inline-error[data-target="sources[1].radius"]').textContent(), /radius.*positive/);
  // Typing a valid radius in that field remeshes.
  await radiusRow.locator('input').fill('0.4');
  await radiusRow.locator('input').press('Enter');
  await settle(page);
  r = await page.evaluate(() => window.anisomeshApp.state.lastError);
  assert.equal(r, null);
  assert.equal(await page.locator('.inline-error').count(), 0);

  // 3. A self-intersecting contour typed in the domain box.
  await page.locator('#domain-box summary').click();
  await page.locator('#domain-json').fill(JSON.stringify({ outer: [{ type: 'polyline', points: [[0, 0], [10, 5], [10, 0], [0, 5], [0, 0]] }] }));
  await page.locator('#domain-apply').click();
  await page.waitForFunction(() => window.anisomeshApp.state.lastError?.code === 'SELF_INTERSECTING_CONTOUR' && window.anisomeshApp.idle());
  assert.equal(await page.locator('#error-domain').isVisible(), true);
  assert.match(await page.locator('#error-domain').textContent(), /intersects itself/);
  assert.equal(await page.evaluate(() => window.anisomeshApp.views.mesh.triangles.length / 3), meshBefore);
  // A plain rectangle meshes again.
  await page.locator('#domain-json').fill(JSON.stringify({ outer: [{ type: 'polyline', points: [[0, 0], [10, 0], [10, 5], [0, 5], [0, 0]] }] }));
  await page.locator('#domain-apply').click();
  await page.waitForFunction(() => window.anisomeshApp.state.lastError === null && window.anisomeshApp.idle());
  assert.equal(await page.locator('#error-domain').isVisible(), false);

  // 4. The element budget: error next to "max elements".
  const maxRow = page.locator('#gui .lil-controller', { hasText: 'max elements' });
  await maxRow.locator('input').fill('50');
  await maxRow.locator('input').press('Enter');
  await page.waitForFunction(() => window.anisomeshApp.state.lastError?.code === 'ELEMENT_BUDGET_EXCEEDED' && window.anisomeshApp.idle());
  assert.match(await page.locator('.inline-error[data-target="maxElements"]').textContent(), /budget/);
  await maxRow.locator('input').fill('2000000');
  await maxRow.locator('input').press('Enter');
  await page.waitForFunction(() => window.anisomeshApp.state.lastError === null && window.anisomeshApp.idle());

  // 5. A value the core rejects (hmin > hmax) lands next to hmin.
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.controlSpace.hmin = 5; a.edited(0); });
  assert.equal(await page.locator('.inline-error[data-target="hmin"]').count(), 1);
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.controlSpace.hmin = 0.01; a.edited(0); });
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.lastError), null);
  assert.deepEqual(errors, []);
  await page.close();
});

test('an error shows at the top of the view and the status no longer says meshed; a fix clears both', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('holes-off'));
  assert.match(await page.locator('#status-text').textContent(), /^meshed in/);
  assert.equal(await page.locator('#view-error').isVisible(), false);
  // The panel scrolled to its end: the control's own message is out of sight there.
  await page.evaluate(() => { const p = document.getElementById('panel'); p.scrollTop = p.scrollHeight; });
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.sources[1].radius = 0; a.edited(0); });
  const banner = page.locator('#view-error');
  assert.equal(await banner.isVisible(), true);
  assert.match(await banner.textContent(), /^[A-Z_]+: .*radius.*positive.*\(previous mesh shown\)$/);
  const [b, v] = await Promise.all([banner.boundingBox(), page.locator('#view').boundingBox()]);
  const viewport = page.viewportSize();
  assert.ok(b.y >= v.y && b.y + b.height <= v.y + 80 && b.y + b.height <= viewport.height, `banner at ${JSON.stringify(b)}, view ${JSON.stringify(v)}`);
  const status = await page.locator('#status-text').textContent();
  assert.doesNotMatch(status, /meshed/);
  assert.match(status, /input error/);
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.sources[1].radius = 0.4; a.edited(0); });
  assert.equal(await banner.isVisible(), false);
  assert.match(await page.locator('#status-text').textContent(), /^meshed in/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a surface preset with quads draws its quads in both views', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('sphere'));
  const triangleOnly = await page.evaluate(() => window.anisomeshApp.state.lastStats.triangles);
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.options.quads = true; a.edited(0); });
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp;
    const m = a.views.mesh;
    return {
      error: a.state.lastError,
      stats: a.state.lastStats,
      drawnQuads: m.quads.length / 4,
      surface: m.dimension === 3,
      cov2: a.coverage('2d'),
      cov3: a.coverage('3d'),
    };
  });
  assert.equal(r.error, null, JSON.stringify(r.error));
  assert.ok(r.surface);
  assert.ok(r.stats.quads > 0, `quads: ${r.stats.quads}`);
  assert.equal(r.drawnQuads, r.stats.quads);
  assert.ok(r.stats.triangles < triangleOnly, `${r.stats.triangles} triangles left of ${triangleOnly}`);
  assert.ok(r.cov2 > 0.05 && r.cov3 > 0.05, `coverage ${r.cov2} ${r.cov3}`);
  assert.equal(await statValue(page, 'quads'), String(r.stats.quads));
  assert.deepEqual(errors, []);
  await page.close();
});

test('the state is kept in the URL and a shared link restores it', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('point-source'));
  await settle(page, () => {
    const a = window.anisomeshApp;
    a.state.case.sources[0].center = [1.1, 0.6];
    a.state.case.options.quads = true;
    a.edited(0);
  });
  await page.evaluate(() => new Promise((r) => setTimeout(r, 400)));  // the hash is written after 250 ms
  const hash = await page.evaluate(() => location.hash);
  assert.match(hash, /^#s=[A-Za-z0-9_-]+$/);
  const quads = await page.evaluate(() => window.anisomeshApp.state.lastStats.quads);
  assert.ok(quads > 0, 'quad-dominant mesh');
  await page.close();

  const { page: page2, errors: errors2 } = await openPage(env.browser, env.url, { hash });
  const r = await page2.evaluate(() => {
    const a = window.anisomeshApp;
    return { preset: a.state.presetId, center: a.state.case.sources[0].center, quads: a.state.lastStats.quads, error: a.state.lastError };
  });
  assert.deepEqual(r, { preset: 'point-source', center: [1.1, 0.6], quads, error: null });
  assert.deepEqual([...errors, ...errors2], []);
  await page2.close();
});

// Runs in the page: a heavy job (~80k triangles, several hundred ms in the worker) on the
// point-source preset, superseded once the worker has started it (after `waitMs` more) by a
// coarse input; resolves when the app is idle again.
async function supersedeHeavyJob(waitMs) {
  const a = window.anisomeshApp;
  a.state.case.sources[0].h0 = 0.0005;
  a.state.case.controlSpace.hmin = 0.0005;
  a.edited(0);
  const spinner = document.querySelector('#status .spinner');
  while (spinner.hidden) await new Promise((res) => setTimeout(res, 5));
  await new Promise((res) => setTimeout(res, waitMs));
  a.state.case.sources[0].h0 = 0.01;
  a.state.case.controlSpace.hmin = 0.002;
  a.edited(0);
  await a.whenIdle();
}

test('a new job supersedes a running one (the worker is replaced) and the last input wins', async () => {
  // Without cross-origin isolation (as on a host that does not send COOP / COEP): the
  // worker is terminated and the spare takes over.
  const { page, errors } = await openPage(env.browser, env.url + '?isolation=off');
  assert.equal(await page.evaluate(() => globalThis.crossOriginIsolated), false);
  await settle(page, () => window.anisomeshApp.loadPreset('point-source'));
  const cancelledBefore = await page.evaluate(() => window.anisomeshApp.state.cancelled);
  await page.evaluate(supersedeHeavyJob, 0);
  const r = await page.evaluate(async (cancelledBefore) => {
    const a = window.anisomeshApp;
    // The cancellation's replacement spare starts once the runner is idle (a task later).
    const t0 = performance.now();
    while (!a.meshRunner.spare && performance.now() - t0 < 5000) await new Promise((res) => setTimeout(res, 10));
    await a.meshRunner.spare?.ready;
    return { spareAgain: Boolean(a.meshRunner.spare?.isReady), spareSwaps: a.meshRunner.spareSwaps, cancelled: a.state.cancelled - cancelledBefore, meshed: a.state.meshedVersion, version: a.state.caseVersion, restartMs: a.state.workerRestartMs, error: a.state.lastError, tris: a.state.lastStats.triangles };
  }, cancelledBefore);
  assert.equal(r.error, null);
  assert.ok(r.cancelled >= 1, `cancelled ${r.cancelled}`);
  assert.equal(r.meshed, r.version, 'the mesh on screen is the latest input');
  assert.ok(r.tris < 20000, `the coarse (last) input is on screen: ${r.tris} triangles`);
  assert.ok(r.restartMs.length >= 1);
  // The spare worker, instantiated ahead of time, took over the cancelled one's place.
  assert.ok(r.spareSwaps >= 1, `spare swaps ${r.spareSwaps}`);
  // ...and a new spare is ready for the next cancellation.
  assert.ok(r.spareAgain, 'a new spare worker after the cancellation');
  console.log(`# worker restart (precompiled module): ${r.restartMs.join(', ')} ms`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('on an isolated page a superseded mesh job is stopped inside its worker, which stays, and the last input wins', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('point-source'));
  await page.evaluate(() => {
    const a = window.anisomeshApp;
    window.beforeSupersede = { cancelled: a.state.cancelled, restarts: a.meshRunner.restarts, stopped: a.meshRunner.stoppedInWorker, worker: a.meshRunner.worker };
  });
  await page.evaluate(supersedeHeavyJob, 30);  // superseded inside the core
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp, before = window.beforeSupersede, worker = before.worker;
    return {
      isolated: globalThis.crossOriginIsolated, sameWorker: a.meshRunner.worker === worker,
      cancelled: a.state.cancelled - before.cancelled, restarts: a.meshRunner.restarts - before.restarts,
      stopped: a.meshRunner.stoppedInWorker - before.stopped, meshed: a.state.meshedVersion, version: a.state.caseVersion,
      error: a.state.lastError, tris: a.state.lastStats.triangles,
    };
  });
  assert.equal(r.isolated, true, 'the dev server sends COOP / COEP');
  assert.equal(r.error, null);
  assert.ok(r.cancelled >= 1, `cancelled ${r.cancelled}`);
  // The core stopped the heavy job (its CANCELLED result came back) in the same worker.
  assert.ok(r.stopped >= 1, `jobs stopped in the worker: ${r.stopped}`);
  assert.equal(r.restarts, 0, 'no worker was terminated');
  assert.ok(r.sameWorker, 'the same worker ran the last input');
  assert.equal(r.meshed, r.version, 'the mesh on screen is the latest input');
  assert.ok(r.tris < 20000, `the coarse (last) input is on screen: ${r.tris} triangles`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a dimension-3 mesh (surface) renders in the 3D view, its (u, v) in the 2D view', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await page.evaluate(() => window.anisomeshApp.setView({ view: '2d' }));
  const tris = await page.evaluate(sphereMesh, 2000);
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp;
    return { mode: a.state.view.view, dim: a.views.mesh.dimension, cov2: a.coverage('2d'), cov3: a.coverage('3d'), tris: a.views.mesh.triangles.length / 3 };
  });
  assert.equal(r.dim, 3);
  assert.equal(r.tris, tris);
  assert.equal(r.mode, 'split', 'a surface mesh brings up the 3D view');
  assert.ok(r.cov3 > 0.05, `3D coverage ${r.cov3}`);
  assert.ok(r.cov2 > 0.05, `2D coverage ${r.cov2}`);
  assert.equal(await statValue(page, 'triangles'), String(tris));
  assert.deepEqual(errors, []);
  await page.close();
});

test('the page keeps animating while the core meshes, and the toolbar shows the running job', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('point-source'));
  const r = await page.evaluate(async () => {
    const a = window.anisomeshApp;
    // A fine case (~130k triangles) so that the job lasts long enough to watch.
    a.state.case.sources[0].h0 = 0.0004;
    a.state.case.controlSpace.hmin = 0.0004;
    a.state.case.controlSpace.hmax = 0.0065;
    a.edited(0);
    let frames = 0, busyFrames = 0, busySeen = false, text = '';
    // Watch the spinner itself (not once per frame: a software-rendered frame can outlast the job).
    const spinner = document.querySelector('#status .spinner');
    const observer = new MutationObserver(() => {
      if (!busySeen && !spinner.hidden) {
        busySeen = true;
        text = document.getElementById('status-text').textContent;
      }
    });
    observer.observe(spinner, { attributes: true });
    const t0 = performance.now();
    await new Promise((res) => {
      const f = () => {
        frames++;
        if (!spinner.hidden) busyFrames++;
        if (a.idle() && frames > 2) res(); else requestAnimationFrame(f);
      };
      requestAnimationFrame(f);
    });
    observer.disconnect();
    return { frames, busyFrames, ms: performance.now() - t0, busySeen, text, tris: a.state.lastStats.triangles };
  });
  assert.ok(r.busySeen, 'busy indicator shown');
  assert.match(r.text, /^(starting|control space|boundary|inserting points|improving|finishing|quality report)( \d+ %)? · \d+\.\d s$/);
  assert.ok(r.tris > 20000, `${r.tris} triangles`);
  // The main thread is free during the job: the page keeps rendering frames while the
  // worker meshes (a count, not a rate: frame rates are measured in the bench script).
  assert.ok(r.busyFrames >= 2, `${r.busyFrames} frames drawn while the job ran (${r.frames} in ${Math.round(r.ms)} ms)`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a long run shows the core\'s progress (stage and percentage) in the toolbar', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('point-source'));
  const r = await page.evaluate(async () => {
    const a = window.anisomeshApp;
    const firstJob = a.meshRunner.nextId;
    const texts = [], bar = [];
    const statusText = document.getElementById('status-text'), progress = document.getElementById('progress');
    const observer = new MutationObserver(() => {
      texts.push(statusText.textContent);
      if (!progress.hidden) bar.push({ now: Number(progress.getAttribute('aria-valuenow')), width: progress.querySelector('.fill').style.width });
    });
    observer.observe(document.getElementById('status'), { subtree: true, childList: true, characterData: true, attributes: true });
    // ~70k triangles: the mesher reports a fraction every 4096 inserted points.
    a.state.case.sources[0].h0 = 0.0005;
    a.state.case.controlSpace.hmin = 0.0005;
    a.state.case.controlSpace.hmax = 0.009;
    a.edited(0);
    await a.whenIdle();
    observer.disconnect();
    return {
      log: a.state.progressLog.filter((e) => e.id >= firstJob),
      texts, bar,
      barHiddenAfter: progress.hidden,
      tris: a.state.lastStats.triangles,
      error: a.state.lastError,
    };
  });
  assert.equal(r.error, null);
  assert.ok(r.tris > 50000, `${r.tris} triangles`);
  const stages = r.log.map((e) => e.stage);
  assert.ok(stages.includes('inserting points'), `stages: ${stages}`);
  const inserting = r.log.filter((e) => e.stage === 'inserting points');
  assert.ok(inserting.every((e) => e.fraction > 0 && e.fraction < 1), JSON.stringify(inserting));
  // Within the job the fraction only grows, and the last stage is the quality report.
  const fractions = r.log.filter((e) => e.fraction != null).map((e) => e.fraction);
  assert.ok(fractions.every((f, i) => i === 0 || f >= fractions[i - 1]), `fractions ${fractions}`);
  assert.equal(stages.at(-1), 'quality report');
  // The toolbar showed the stage with a percentage, and the bar filled part way.
  assert.ok(r.texts.some((t) => /^inserting points \d+ % · \d+\.\d s$/.test(t)), `texts: ${r.texts.slice(0, 8)}`);
  assert.ok(r.bar.some((b) => b.now > 0 && b.now < 100 && parseFloat(b.width) > 0), JSON.stringify(r.bar.slice(0, 5)));
  assert.equal(r.barHiddenAfter, true, 'the bar goes away when the job is done');
  assert.deepEqual(errors, []);
  await page.close();
});

test('the control-space overlay is inspected only when shown', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('holes-dr2'));
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.overlay), null);
  await settle(page, () => window.anisomeshApp.setView({ controlSpace: true }));
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp;
    return { nodes: a.state.overlay?.nodes.length ?? 0, legend: a.views.controlLegend, text: document.getElementById('legend').textContent };
  });
  assert.ok(r.nodes > 0 && r.legend?.count === r.nodes / 5, JSON.stringify(r.legend));
  assert.match(r.text, /control space h .*nodes/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a sources-only change redraws the sources over the cached 2D mesh image', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('holes-dr2'));
  const r = await page.evaluate(async () => {
    const a = window.anisomeshApp, v = a.views;
    const frame = () => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res)));
    await frame();
    const before = { cached: v.cache2Draws, frames: v.framesRendered, cov: v.coverage('2d') };
    a.selectSource(a.state.selected === 0 ? 1 : 0);  // the selection colour changes, the mesh does not
    await frame();
    const mid = { cached: v.cache2Draws, frames: v.framesRendered };
    v.fit2D([0, 0, 5, 2]);  // the camera changes: the image is redrawn
    await frame();
    return { before, mid, after: { cached: v.cache2Draws, cov: v.coverage('2d') } };
  });
  assert.ok(r.mid.frames > r.before.frames, 'a frame was drawn for the selection');
  assert.equal(r.mid.cached, r.before.cached, 'the mesh image was reused');
  assert.ok(r.after.cached > r.mid.cached, 'a camera change redraws the mesh image');
  assert.ok(r.before.cov > 0.05 && r.after.cov > 0.05, JSON.stringify(r));
  assert.deepEqual(errors, []);
  await page.close();
});

test('the element edges are drawn over the faces in both views, by length or plain, and not when off', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('holes-dr2'));
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp, v = a.views;
    // The canvas's RGBA pixels with the given edge colouring (sources hidden).
    const pixels = (edges) => {
      a.setView({ edges, sources: false, view: 'split' });
      v.requestRender();
      v.render();
      const c = document.createElement('canvas');
      c.width = v.canvas.width; c.height = v.canvas.height;
      const ctx = c.getContext('2d');
      ctx.drawImage(v.canvas, 0, 0);
      return ctx.getImageData(0, 0, c.width, c.height).data;
    };
    const off = pixels('off'), plain = pixels('plain'), length = pixels('length');
    // Fraction of the pixels of a view ('2d' | '3d') that differ between two pictures.
    const ratio = v.canvas.width / v.container.clientWidth;
    const differ = (p, q, which) => {
      const vp = v.viewports()[which], w = v.canvas.width;
      let n = 0, all = 0;
      for (let y = Math.round(vp.y * ratio); y < Math.round((vp.y + vp.h) * ratio); y++) {
        for (let x = Math.round(vp.x * ratio); x < Math.round((vp.x + vp.w) * ratio); x++, all++) {
          const i = 4 * (y * w + x);
          if (Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 24) n++;
        }
      }
      return n / all;
    };
    return {
      plain2: differ(off, plain, '2d'), plain3: differ(off, plain, '3d'),
      length2: differ(plain, length, '2d'), length3: differ(plain, length, '3d'),
      again: differ(off, pixels('off'), '2d'),
    };
  });
  assert.ok(r.plain2 > 0.02 && r.plain3 > 0.005, `edges drawn: ${JSON.stringify(r)}`);
  assert.ok(r.length2 > 0.01 && r.length3 > 0.01, `length colours differ from plain: ${JSON.stringify(r)}`);
  assert.equal(r.again, 0, 'edges off twice: the same picture');
  assert.deepEqual(errors, []);
  await page.close();
});

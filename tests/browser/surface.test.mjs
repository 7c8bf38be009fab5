// Surface cases in the page: the control-space overlay, quality colours and histograms,
// the patches of a two-patch case side by side in (u, v), the surface metric controls,
// and round trips (case download -> file input or drop, control-space downloads, URL).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, readFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { dragSourceOnce, launch, openPage, openSurfaceDragPage, settle } from './launch.mjs';

let env, dir;
before(async () => {
  env = await launch();
  dir = await mkdtemp(join(tmpdir(), 'anisomesh-surface-'));
});
after(async () => { await env?.close(); });

// The `count` downloads one click on a download button starts (a surface's control
// space: one file per patch).
async function downloadFrom(page, kind, count = 1) {
  const got = [];
  let done;
  const all = new Promise((r) => { done = r; });
  const onDownload = (dl) => { got.push(dl); if (got.length === count) done(); };
  page.on('download', onDownload);
  await page.locator(`#downloads button[data-dl="${kind}"]`).click();
  await all;
  page.off('download', onDownload);
  const out = [];
  for (const dl of got) {
    const path = join(dir, dl.suggestedFilename());
    await dl.saveAs(path);
    out.push({ name: dl.suggestedFilename(), path, text: await readFile(path, 'utf8') });
  }
  return out.sort((a, b) => a.name.localeCompare(b.name));
}

// A digest of the mesh on screen (vertices and connectivity), to compare two meshes exactly.
const meshDigest = (m = window.anisomeshApp.views.mesh) => {
  let h = 0;
  const mix = (x) => { h = (Math.imul(h, 31) + x) | 0; };
  for (const x of new Int32Array(new Float64Array(m.vertices).buffer)) mix(x);
  for (const t of m.triangles) mix(t);
  for (const q of m.quads) mix(q);
  return { h, vertices: m.vertices.length / 3, triangles: m.triangles.length / 3 };
};

test('a surface preset shows its control space, quality colours and histogram data', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('p2-holes'));
  await settle(page, () => window.anisomeshApp.setView({ controlSpace: true, colorBy: 'quality' }));
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp;
    const q = a.state.lastMeasures.quality;
    return {
      glyphs: a.state.overlay?.glyphs?.patch.length ?? 0,
      legend: a.views.controlLegend,
      text: document.getElementById('legend').textContent,
      quality: q ? q.length : 0, elements: a.views.mesh.triangles.length / 3 + a.views.mesh.quads.length / 4,
      qmin: q ? Math.min(...q) : null, qmean: a.state.lastStats.quality.mean,
      qmeanPage: q ? q.reduce((s, x) => s + x, 0) / q.length : null,
      lines3: a.views.control3.children.length,
      lengths: a.state.lastMeasures.edgeLength?.length ?? 0, edges: a.state.lastMeasures.edges.length / 2,
      lmeanPage: a.state.lastMeasures.edgeLength ? a.state.lastMeasures.edgeLength.reduce((s, x) => s + x, 0) / a.state.lastMeasures.edgeLength.length : null,
      lmean: a.state.lastStats.edgeLength.mean,
    };
  });
  assert.ok(r.glyphs > 20, `control-space ellipses: ${r.glyphs}`);
  assert.equal(r.legend?.count, r.glyphs);
  assert.match(r.text, /control space h .*ellipses/);
  assert.equal(r.lines3, 1, 'the ellipses are drawn on the surface in 3D too');
  // One 3D quality per element, the ones the report averages.
  assert.equal(r.quality, r.elements);
  assert.ok(Math.abs(r.qmeanPage - r.qmean) < 1e-4, `${r.qmeanPage} vs report ${r.qmean}`);
  // One 3D metric length per distinct edge, the ones the report averages.
  assert.equal(r.lengths, r.edges);
  assert.ok(Math.abs(r.lmeanPage - r.lmean) < 1e-4, `${r.lmeanPage} vs report ${r.lmean}`);
  // The quality histogram has data: its canvas is not only the "no data" text.
  for (const id of ['hist-quality', 'hist-length']) {
  const hist = await page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let coloured = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - d[i + 1]) > 40 || Math.abs(d[i + 1] - d[i + 2]) > 40) coloured++;
    return coloured;
  }, id);
  assert.ok(hist > 200, `${id}: coloured histogram pixels: ${hist}`);
  }
  assert.deepEqual(errors, []);
  await page.close();
});

test('the two patches of figs. 11-13 are drawn side by side in (u, v), never overlapping', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('two-patch-c'));
  await settle(page, () => window.anisomeshApp.setView({ controlSpace: true }));
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp, v = a.views, L = v.layout, m = v.mesh;
    const elem = v.result.patches.element;
    const nt = m.triangles.length / 3;
    // (u) range of each patch's laid-out corners.
    const lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
    for (let e = 0; e < nt; e++) for (let k = 0; k < 3; k++) {
      const u = L.uv[3 * (3 * e + k)];
      lo[elem[e]] = Math.min(lo[elem[e]], u); hi[elem[e]] = Math.max(hi[elem[e]], u);
    }
    // Ellipses of patch 1 lie in patch 1's strip.
    const g = a.state.overlay.glyphs;
    let outside = 0;
    for (let i = 0; i < g.patch.length; i++) {
      for (let k = g.offsets[i]; k < g.offsets[i + 1]; k++) {
        const u = g.uv[2 * k] + L.shift[g.patch[i]];
        if (u < lo[g.patch[i]] - 0.05 || u > hi[g.patch[i]] + 0.05) outside++;
      }
    }
    return { lo, hi, bounds: L.bounds, boundary: L.boundary.length / 2, outside, patches: [...new Set(g.patch)] };
  });
  assert.ok(r.hi[0] < r.lo[1], `patch strips overlap: ${JSON.stringify(r)}`);
  assert.ok(Math.abs(r.hi[0] - r.lo[0] - 1) < 1e-6 && Math.abs(r.hi[1] - r.lo[1] - 1) < 1e-6, JSON.stringify(r));
  assert.deepEqual(r.patches, [0, 1]);
  assert.equal(r.outside, 0);
  assert.ok(r.boundary > 0);
  assert.deepEqual(errors, []);
  await page.close();
});

// Near-black pixels of a viewport, drawn now (the faces are light: a freed GPU buffer draws black).
const darkPixels = (which) => {
  const v = window.anisomeshApp.views;
  v.invalidate2D();
  v.renderNow([which], { sync: true });
  const vp = v.viewports()[which], c = document.createElement('canvas');
  c.width = v.canvas.width; c.height = v.canvas.height;
  const ctx = c.getContext('2d');
  ctx.drawImage(v.canvas, 0, 0);
  const d = ctx.getImageData(vp.x, vp.y, vp.w, vp.h).data;
  let n = 0;
  for (let i = 0; i < d.length; i += 4) if (d[i] < 20 && d[i + 1] < 20 && d[i + 2] < 20) n++;
  return n;
};

test('a surface mesh that outgrows its arrays is drawn in colour in both views (no freed buffers)', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('two-patch-c'));
  const before = await page.evaluate(() => window.anisomeshApp.views.mesh.triangles.length / 3);
  // 7.8k -> 9.8k triangles: more than the arrays' 25 % slack, so the 2D geometry's arrays
  // are replaced while the 3D geometry shares its colours.
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.metric.hmax = 0.04; a.edited(0); });
  const after = await page.evaluate(() => window.anisomeshApp.views.mesh.triangles.length / 3);
  assert.ok(after > 1.25 * before, `${before} -> ${after} triangles`);
  const dark = { '2d': await page.evaluate(darkPixels, '2d'), '3d': await page.evaluate(darkPixels, '3d') };
  assert.ok(dark['2d'] < 50 && dark['3d'] < 50, `near-black pixels: ${JSON.stringify(dark)}`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a surface\'s stats panel has no empty rows, and a surface made 3 times larger is fitted again', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('sphere'));
  await page.waitForFunction(() => document.querySelector('#stats dd[data-key="Q min / mean"]')?.textContent.includes('/'));
  const rows = await page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#stats dd')].map((d) => [d.dataset.key, d.textContent])));
  assert.ok(Number(rows.edges) > 1000, `edges: ${rows.edges}`);
  for (const [k, v] of Object.entries(rows)) assert.ok(!/^–$|–,|, –|undefined/.test(v), `row ${k}: ${v}`);
  assert.equal(rows['len in [0.6, 1.3]'], undefined, 'a row the surface report has no value for');
  const r0 = await page.evaluate(() => window.anisomeshApp.views.fitted3.r);
  await settle(page, () => { const a = window.anisomeshApp; a.state.case.patches[0].surface.radius = 3; a.edited(0); });
  const r1 = await page.evaluate(() => window.anisomeshApp.views.fitted3.r);
  assert.ok(Math.abs(r1 / r0 - 3) < 0.1, `fitted radius ${r0} -> ${r1}`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a surface case downloads and loads back (file input and drop) with an identical mesh', async () => {
  const { page, errors } = await openPage(env.browser, env.url, { acceptDownloads: true });
  await settle(page, () => window.anisomeshApp.loadPreset('two-patch-c'));
  const before = await page.evaluate(meshDigest);
  const [c] = await downloadFrom(page, 'case');
  assert.ok(JSON.parse(c.text).patches.length === 2);
  // Control space: one VTK per patch, a JSON with both.
  const vtk = await downloadFrom(page, 'cs-vtk', 2);
  assert.match(vtk[0].name, /_control_space_patch0\.vtk$/);
  assert.match(vtk[1].name, /_control_space_patch1\.vtk$/);
  for (const f of vtk) assert.match(f.text, /^# vtk DataFile[\s\S]*TENSORS metric/);
  const [json] = await downloadFrom(page, 'cs-json');
  assert.equal(JSON.parse(json.text).patches.length, 2);

  await settle(page, () => window.anisomeshApp.loadPreset('holes-dr2'));
  await page.locator('#case-file').setInputFiles(c.path);
  await page.waitForFunction(() => window.anisomeshApp.state.surface && window.anisomeshApp.state.presetId === 'custom');
  await settle(page);
  assert.deepEqual(await page.evaluate(meshDigest), before);
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.lastError), null);

  // Dropped on the page.
  await settle(page, () => window.anisomeshApp.loadPreset('holes-dr2'));
  await page.evaluate(async (text) => {
    const dt = new DataTransfer();
    dt.items.add(new File([text], 'dropped.json', { type: 'application/json' }));
    document.getElementById('view').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, c.text);
  await page.waitForFunction(() => window.anisomeshApp.state.surface);
  await settle(page);
  assert.deepEqual(await page.evaluate(meshDigest), before);
  assert.deepEqual(errors, []);
  await page.close();
});

test('surface metric controls remesh and the state of a surface case is kept in the URL', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('p2-holes'));
  const t0 = await page.evaluate(() => window.anisomeshApp.views.mesh.triangles.length / 3);
  // The panel's chord tolerance: a coarser tolerance gives fewer triangles.
  const input = page.locator('.lil-gui .lil-controller', { hasText: 'chord tolerance' }).locator('input');
  await input.fill('0.2');
  await input.press('Enter');
  await page.waitForFunction((n) => window.anisomeshApp.idle() && window.anisomeshApp.views.mesh.triangles.length / 3 !== n, t0);
  const r = await page.evaluate(() => ({ tol: window.anisomeshApp.state.case.metric.chordTolerance, t: window.anisomeshApp.views.mesh.triangles.length / 3 }));
  assert.equal(r.tol, 0.2);
  assert.ok(r.t < t0, `${r.t} triangles at tolerance 0.2, ${t0} at 0.05`);
  // An invalid value (hmin above hmax) shows next to its control; the mesh stays.
  const hmin = page.locator('.lil-gui .lil-controller', { hasText: 'hmin (3D)' }).locator('input');
  await hmin.fill('5');
  await hmin.press('Enter');
  const err = page.locator('.inline-error[data-target="metric.hmin"]');
  await err.waitFor();
  assert.match(await err.textContent(), /INVALID_ARGUMENT: .*hmin <= hmax/);
  assert.equal(await page.evaluate(() => window.anisomeshApp.views.mesh.triangles.length / 3), r.t);
  await hmin.fill('0.02');
  await hmin.press('Enter');
  await page.waitForFunction(() => window.anisomeshApp.idle() && window.anisomeshApp.state.lastError === null);
  // The link restores the surface case.
  await page.waitForFunction(() => location.hash.length > 10);
  await page.waitForTimeout(400);
  const hash = await page.evaluate(() => location.hash);
  const digest = await page.evaluate(meshDigest);
  const second = await openPage(env.browser, env.url, { hash });
  await settle(second.page);
  assert.equal(await second.page.evaluate(() => window.anisomeshApp.state.surface), true);
  assert.deepEqual(await second.page.evaluate(meshDigest), digest);
  assert.deepEqual([...errors, ...second.errors], []);
  await page.close();
  await second.page.close();
});

test('the surface JSON box follows panel edits, and after an Apply the panel edits the applied patches', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('new-heightfield'));
  assert.equal(await page.locator('#expr-box').isHidden(), true, 'the planar size field box is hidden on surfaces');
  const zInput = page.locator('.lil-gui .lil-controller', { hasText: 'z(u, v)' }).locator('input');
  const setZ = async (z) => {
    await zInput.fill(z);
    await zInput.press('Enter');
    await page.waitForFunction((z) => window.anisomeshApp.idle() && window.anisomeshApp.state.case.patches[0].surface.z === z, z);
    await settle(page);
  };
  await setZ('0.3*u*v');
  await page.locator('#domain-box summary').click();
  const box = () => page.locator('#domain-json').inputValue();
  // The box is refreshed by the details element's toggle event, which follows the click.
  const boxHas = (text) => page.waitForFunction((t) => document.getElementById('domain-json').value.includes(t), text, { timeout: 5000 });
  await boxHas('"0.3*u*v"');  // the z typed in the panel
  // Open: it follows further panel edits too.
  await setZ('0.2*u');
  await boxHas('"0.2*u"');
  // An edit in the box (the z in it), applied: then the panel edits the applied patch.
  await page.locator('#domain-json').fill((await box()).replace('"0.2*u"', '"0.1*v"'));
  await page.locator('#domain-apply').click();
  await page.waitForFunction(() => window.anisomeshApp.idle() && window.anisomeshApp.state.case.patches[0].surface.z === '0.1*v');
  await settle(page);
  assert.equal(await zInput.inputValue(), '0.1*v', 'the panel shows the applied z');
  await setZ('0.25*u*u');
  const r = await page.evaluate(() => ({ z: window.anisomeshApp.state.case.patches[0].surface.z, error: window.anisomeshApp.state.lastError }));
  assert.deepEqual(r, { z: '0.25*u*u', error: null });
  await boxHas('"0.25*u*u"');
  assert.deepEqual(errors, []);
  await page.close();
});

test('the surface JSON box holds the shared curves: a second patch and its shared curve are removed and added there', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('two-patch-c'));
  const patchesOnScreen = () => page.evaluate(() => new Set(window.anisomeshApp.views.result.patches.element).size);
  const digest = await page.evaluate(meshDigest);
  assert.equal(await patchesOnScreen(), 2);
  await page.locator('#domain-box summary').click();
  const text = await page.locator('#domain-json').inputValue();
  const model = JSON.parse(text);
  assert.equal(model.patches.length, 2);
  assert.ok(model.shared?.length >= 1, 'the shared curves are in the box');
  // One patch, no shared curve: applied, one patch is meshed.
  await page.locator('#domain-json').fill(JSON.stringify({ ...model, patches: model.patches.slice(0, 1), shared: undefined }));
  await page.locator('#domain-apply').click();
  await page.waitForFunction(() => window.anisomeshApp.idle() && window.anisomeshApp.state.case.patches.length === 1);
  await settle(page);
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.case.shared), undefined);
  assert.equal(await patchesOnScreen(), 1);
  // The second patch and its shared curve added back: the preset's mesh again.
  await page.locator('#domain-json').fill(text);
  await page.locator('#domain-apply').click();
  await page.waitForFunction(() => window.anisomeshApp.idle() && window.anisomeshApp.state.case.patches.length === 2);
  await settle(page);
  assert.equal(await patchesOnScreen(), 2);
  assert.deepEqual(await page.evaluate(meshDigest), digest);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a height-field patch typed as an expression meshes; an invalid expression shows its error and keeps the mesh', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('new-heightfield'));
  const zInput = page.locator('.lil-gui .lil-controller', { hasText: 'z(u, v)' }).locator('input');
  await zInput.fill('0.4*exp(-4*((u-1)^2+(v-1)^2))');
  await zInput.press('Enter');
  await page.waitForFunction(() => window.anisomeshApp.idle() && window.anisomeshApp.state.case.patches[0].surface.z.startsWith('0.4*exp'));
  await settle(page);
  const r = await page.evaluate(() => {
    const m = window.anisomeshApp.views.mesh;
    let zmax = -Infinity;
    for (let i = 2; i < m.vertices.length; i += 3) zmax = Math.max(zmax, m.vertices[i]);
    return { dim: m.dimension, triangles: m.triangles.length / 3, zmax, error: window.anisomeshApp.state.lastError };
  });
  assert.equal(r.dim, 3);
  assert.equal(r.error, null);
  assert.ok(r.triangles > 100, `${r.triangles} triangles`);
  assert.ok(Math.abs(r.zmax - 0.4) < 0.02, `the bump's top at z = ${r.zmax}`);
  const digest = await page.evaluate(meshDigest);

  // A typo: the core's parse error (with its column) shows under the z field, the mesh stays.
  await zInput.fill('0.4*exp(-4*((u-1)^2+(v-1)^2)');
  await zInput.press('Enter');
  const err = page.locator('.inline-error[data-target="surface.z"]');
  await err.waitFor();
  assert.match(await err.textContent(), /PARSE_ERROR: .*column/);
  assert.deepEqual(await page.evaluate(meshDigest), digest);
  // Fixed: the error goes, a mesh again.
  await zInput.fill('0.2*sin(3*u)');
  await zInput.press('Enter');
  await page.waitForFunction(() => window.anisomeshApp.idle() && window.anisomeshApp.state.lastError === null && window.anisomeshApp.state.case.patches[0].surface.z === '0.2*sin(3*u)');
  assert.equal(await err.count(), 0);
  // Another kind from the panel: a torus.
  await page.locator('.lil-gui .lil-controller', { hasText: 'kind' }).locator('select').selectOption('torus');
  await page.waitForFunction(() => window.anisomeshApp.idle() && window.anisomeshApp.state.case.patches[0].surface.type === 'torus');
  await settle(page);
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.lastError), null);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a source placed by clicking on the 3D surface refines the mesh there; dragging it in 3D remeshes', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('p2-holes'));
  await page.evaluate(() => { window.before = { params: window.anisomeshApp.views.mesh.params.slice(), triangles: window.anisomeshApp.views.mesh.triangles.slice() }; });
  await page.locator('.lil-gui button', { hasText: '+ radial source' }).click();
  // Click on the surface: a point of the 3D view over the mesh (the picked point tells where).
  const at = await page.evaluate(() => {
    const v = window.anisomeshApp.views, vp = v.viewports()['3d'], r = v.canvas.getBoundingClientRect();
    for (const [fx, fy] of [[0.5, 0.5], [0.45, 0.55], [0.55, 0.45], [0.4, 0.5]]) {
      const x = r.left + vp.x + fx * vp.w, y = r.top + vp.y + fy * vp.h;
      if (v.pick3D(x, y)) return { x, y };
    }
    return null;
  });
  assert.ok(at, 'no point of the 3D view hits the surface');
  await page.mouse.click(at.x, at.y);
  await page.waitForFunction(() => window.anisomeshApp.state.lastPlaced);
  await settle(page);
  const placed = await page.evaluate(() => {
    const a = window.anisomeshApp, s = a.state.case.patches[0].sources.at(-1);
    return { s, hit: a.state.lastPlaced, error: a.state.lastError };
  });
  assert.equal(placed.error, null);
  assert.equal(placed.s.type, 'radial');
  assert.ok(Math.hypot(placed.s.center[0] - placed.hit.uv[0], placed.s.center[1] - placed.hit.uv[1]) < 0.01);
  const near = await page.evaluate(([c, r]) => {
    const count = (m) => {
      let n = 0;
      for (let t = 0; t < m.triangles.length; t += 3) {
        let u = 0, v = 0;
        for (let k = 0; k < 3; k++) { u += m.params[2 * m.triangles[t + k]] / 3; v += m.params[2 * m.triangles[t + k] + 1] / 3; }
        if (Math.hypot(u - c[0], v - c[1]) < r) n++;
      }
      return n;
    };
    return { before: count(window.before), after: count(window.anisomeshApp.views.mesh) };
  }, [placed.s.center, placed.s.radius]);
  assert.ok(near.after > 2 * near.before + 10, `triangles near the source: ${near.before} -> ${near.after}`);

  // Drag its handle over the surface in the 3D view.
  const h = await page.evaluate(() => {
    const v = window.anisomeshApp.views, h = v.handles3.find((x) => x.key === 'center');
    return h ? v.worldToClient3(h.xyz) : null;
  });
  assert.ok(h, 'the source has a handle in the 3D view');
  const digest = await page.evaluate(meshDigest);
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  for (let k = 1; k <= 5; k++) await page.mouse.move(h.x + 8 * k, h.y + 5 * k);
  // While held, the 3D view's handles are drawn by the page (the SVG overlay), not by WebGL.
  const held = await page.evaluate(() => {
    const v = window.anisomeshApp.views;
    const rects = [...v.dragOverlay.querySelectorAll('rect')].map((r) => {
      const b = r.getBoundingClientRect();
      return [b.x + b.width / 2, b.y + b.height / 2];
    });
    return { view: v.sourcesInOverlay, shown: v.dragOverlay.style.display !== 'none', webgl: v.sources3.visible, rects };
  });
  assert.ok(held.view === '3d' && held.shown && !held.webgl, JSON.stringify(held));
  assert.ok(held.rects.some(([x, y]) => Math.hypot(x - (h.x + 40), y - (h.y + 25)) < 3), `a handle under the pointer: ${JSON.stringify(held.rects)}`);
  await page.mouse.up();
  await settle(page);
  assert.equal(await page.evaluate(() => window.anisomeshApp.views.sources3.visible), true);
  const moved = await page.evaluate(() => window.anisomeshApp.state.case.patches[0].sources.at(-1).center);
  assert.notDeepEqual(moved, placed.s.center);
  assert.notDeepEqual(await page.evaluate(meshDigest), digest);
  const nearMoved = await page.evaluate(([c, r]) => {
    const count = (m) => {
      let n = 0;
      for (let t = 0; t < m.triangles.length; t += 3) {
        let u = 0, v = 0;
        for (let k = 0; k < 3; k++) { u += m.params[2 * m.triangles[t + k]] / 3; v += m.params[2 * m.triangles[t + k] + 1] / 3; }
        if (Math.hypot(u - c[0], v - c[1]) < r) n++;
      }
      return n;
    };
    return { before: count(window.before), after: count(window.anisomeshApp.views.mesh) };
  }, [moved, placed.s.radius]);
  assert.ok(nearMoved.after > 2 * nearMoved.before + 10, `triangles near the moved source: ${JSON.stringify(nearMoved)}`);
  // The release's mesh came without its colours (drawn sooner); the report brought them:
  // one 3D quality per element of the mesh on screen.
  const colours = await page.evaluate(() => {
    const a = window.anisomeshApp, m = a.views.mesh;
    return { quality: a.state.lastMeasures.quality?.length ?? 0, elements: m.triangles.length / 3 + m.quads.length / 4 };
  });
  assert.equal(colours.quality, colours.elements);
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.lastError), null);
  assert.deepEqual(errors, []);
  await page.close();
});

test('an SVG drawing with a hole becomes the domain and meshes', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  const svg = `<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 60">
    <path d="M0,0 H80 Q100,0 100,20 V60 H0 Z"/>
    <circle cx="40" cy="30" r="12"/>
  </svg>`;
  const file = join(dir, 'drawing.svg');
  await (await import('node:fs/promises')).writeFile(file, svg);
  await page.locator('#svg-size').fill('2');
  await page.locator('#svg-file').setInputFiles(file);
  await page.waitForFunction(() => window.anisomeshApp.state.case?.name === 'drawing');
  await settle(page);
  const r = await page.evaluate(() => {
    const a = window.anisomeshApp, m = a.views.mesh, d = a.state.case.domain;
    // The hole: a circle of radius 12/100*2 = 0.24 at (0.8, (60-30)/100*2 = 0.6).
    let inside = 0;
    for (let t = 0; t < m.triangles.length; t += 3) {
      let x = 0, y = 0;
      for (let k = 0; k < 3; k++) { x += m.vertices[2 * m.triangles[t + k]] / 3; y += m.vertices[2 * m.triangles[t + k] + 1] / 3; }
      if (Math.hypot(x - 0.8, y - 0.6) < 0.2) inside++;
    }
    let xmax = 0, ymax = 0;
    for (let i = 0; i < m.vertices.length; i += 2) { xmax = Math.max(xmax, m.vertices[i]); ymax = Math.max(ymax, m.vertices[i + 1]); }
    return { holes: d.holes.length, outer: d.outer.map((c) => c.type), triangles: m.triangles.length / 3, inside, xmax, ymax, error: a.state.lastError, surface: a.state.surface };
  });
  assert.equal(r.error, null);
  assert.equal(r.surface, false);
  assert.equal(r.holes, 1);
  assert.ok(r.outer.includes('bezier') && r.outer.includes('line'), r.outer.join());
  assert.ok(r.triangles > 200, `${r.triangles} triangles`);
  assert.equal(r.inside, 0, 'no triangle inside the hole');
  assert.ok(Math.abs(r.xmax - 2) < 1e-6 && Math.abs(r.ymax - 1.2) < 1e-6, `${r.xmax} x ${r.ymax}`);
  // A drawing that is no domain: the core's message, the mesh stays.
  const bad = join(dir, 'open.svg');
  await (await import('node:fs/promises')).writeFile(bad, '<svg><path d="M0 0 L1 0 L1 1"/></svg>');
  await page.locator('#svg-file').setInputFiles(bad);
  await page.locator('#error-io').waitFor({ state: 'visible' });
  assert.match(await page.locator('#error-io').textContent(), /OPEN_CONTOUR/);
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.case.name), 'drawing');
  assert.deepEqual(errors, []);
  await page.close();
});

test('undo and redo step through edits (panel edits and a new case)', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, () => window.anisomeshApp.loadPreset('p2-holes'));
  const d0 = await page.evaluate(meshDigest);
  const input = page.locator('.lil-gui .lil-controller', { hasText: 'chord tolerance' }).locator('input');
  await input.fill('0.2');
  await input.press('Enter');
  await page.waitForFunction(() => window.anisomeshApp.state.case.metric.chordTolerance === 0.2);
  await settle(page);
  const d1 = await page.evaluate(meshDigest);
  assert.notDeepEqual(d1, d0);
  await page.locator('#undo').click();
  await page.waitForFunction(() => window.anisomeshApp.state.case.metric.chordTolerance === 0.05);
  await settle(page);
  assert.deepEqual(await page.evaluate(meshDigest), d0);
  assert.equal(await input.inputValue(), '0.05');
  // Keyboard redo (focus on the canvas, not in a text field).
  await page.locator('#view canvas').focus();
  await page.keyboard.press('Control+Shift+Z');
  await page.waitForFunction(() => window.anisomeshApp.state.case.metric.chordTolerance === 0.2);
  await settle(page);
  assert.deepEqual(await page.evaluate(meshDigest), d1);
  // A new case is a step too: undo brings the surface back.
  await settle(page, () => window.anisomeshApp.loadPreset('holes-dr2'));
  await page.keyboard.press('Control+Z');
  await page.waitForFunction(() => window.anisomeshApp.state.surface === true);
  await settle(page);
  assert.deepEqual(await page.evaluate(meshDigest), d1);
  assert.deepEqual(errors, []);
  await page.close();
});

// Two mesh lanes (cross-origin isolated page): while one worker finishes the job of an
// input the pointer has left, the next input starts at once in the other; a result older
// than the mesh drawn is dropped, so the meshes drawn follow the drag in order and the
// last one is the last input's (the same mesh as a plain remesh of it).
test('a drag on a surface meshes its latest input in a second worker while the first finishes', async () => {
  const { page, errors } = await openSurfaceDragPage(env.browser, env.url);
  await page.waitForFunction(() => window.anisomeshApp.readyLanes() === 2, null, { timeout: 30000 });
  const before = await page.evaluate(() => ({ lane: window.anisomeshApp.state.laneJobs, drawn: window.anisomeshApp.state.meshesDrawn }));
  for (let rep = 0; rep < 3; rep++) await dragSourceOnce(page, rep);
  await settle(page);
  const r = await page.evaluate(() => {
    const s = window.anisomeshApp.state;
    return { lane: s.laneJobs, drawn: s.drawnVersions.slice(), count: s.meshesDrawn, meshed: s.meshedVersion, version: s.caseVersion, error: s.lastError };
  });
  assert.equal(r.error, null);
  assert.ok(r.lane > before.lane, `inputs meshed in the second lane: ${r.lane - before.lane}`);
  // drawnVersions keeps the last 50 only; meshesDrawn counts them all (none drawn: none
  // taken, where slice(-0) would take the whole list).
  const fresh = r.count - before.drawn;
  const drawn = fresh > 0 ? r.drawn.slice(-fresh) : [];
  assert.ok(drawn.length >= 3, `meshes drawn: ${drawn}`);
  for (let k = 1; k < drawn.length; k++) assert.ok(drawn[k] > drawn[k - 1], `meshes drawn out of order: ${drawn}`);
  assert.equal(r.meshed, r.version);
  const digest = await page.evaluate(meshDigest);
  await settle(page, () => window.anisomeshApp.edited(0));
  assert.deepEqual(await page.evaluate(meshDigest), digest, 'the last mesh drawn is not the last input\'s');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a handle dragged in (u, v) is drawn by the page, not by WebGL, until the next mesh is drawn', async () => {
  const { page, errors } = await openSurfaceDragPage(env.browser, env.url);
  const h = await page.evaluate(() => window.anisomeshApp.handleClientPosition(0, 'center'));
  const count = () => page.evaluate(() => ({
    frames: window.anisomeshApp.views.framesRendered, drawn: window.anisomeshApp.state.meshesDrawn,
    recoloured: window.anisomeshApp.state.recolours,
  }));
  const frame = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  await page.mouse.move(h.x + 5, h.y + 3);
  await frame();
  const start = await count();
  for (let k = 2; k <= 7; k++) {
    await page.mouse.move(h.x + 5 * k, h.y + 3 * k);
    await frame();
  }
  const moved = await count();
  // Six moves: WebGL frames only for the meshes drawn meanwhile and for meshes recoloured
  // once their report came in (one of them may have been drawn before the first move);
  // none for the moves themselves.
  const meshes = moved.drawn - start.drawn, recoloured = moved.recoloured - start.recoloured;
  const frames = moved.frames - start.frames;
  assert.ok(frames <= meshes + recoloured, `${frames} frames for ${meshes} meshes drawn and ${recoloured} recoloured`);
  // The handle in the overlay sits under the pointer; the WebGL sources layer is hidden.
  const mid = await page.evaluate(() => {
    const v = window.anisomeshApp.views, box = v.dragOverlay.getBoundingClientRect();
    const rects = [...v.dragOverlay.querySelectorAll('rect')].map((r) => {
      const b = r.getBoundingClientRect();
      return [b.x + b.width / 2, b.y + b.height / 2];
    });
    return { shown: v.dragOverlay.style.display !== 'none' && box.width > 0, rects, lines: v.dragOverlay.querySelectorAll('polyline').length, webgl: v.layers2.sources.visible };
  });
  assert.ok(mid.shown && !mid.webgl, JSON.stringify(mid));
  assert.ok(mid.lines > 0, 'the source outline is in the overlay');
  const near = mid.rects.some(([x, y]) => Math.hypot(x - (h.x + 35), y - (h.y + 21)) < 2);
  assert.ok(near, `a handle under the pointer (${h.x + 35}, ${h.y + 21}): ${JSON.stringify(mid.rects)}`);
  await page.mouse.up();
  await page.waitForFunction(() => window.anisomeshApp.state.dragToMeshMs !== null && window.anisomeshApp.idle(), null, { timeout: 60000 });
  await frame();
  const after = await page.evaluate(() => ({ shown: window.anisomeshApp.views.dragOverlay.style.display !== 'none', webgl: window.anisomeshApp.views.layers2.sources.visible }));
  assert.deepEqual(after, { shown: false, webgl: true });
  assert.deepEqual(errors, []);
  await page.close();
});

test('a drag leaves the toolbar still (no spinner animation, no job progress) until its release', async () => {
  const { page, errors } = await openSurfaceDragPage(env.browser, env.url);
  const h = await page.evaluate(() => window.anisomeshApp.handleClientPosition(0, 'center'));
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  await page.evaluate(() => {
    window.toolbarChanges = [];
    window.toolbarObserver = new MutationObserver((list) => window.toolbarChanges.push(...list.map((m) => m.type)));
    window.toolbarObserver.observe(document.getElementById('status'), { subtree: true, childList: true, characterData: true, attributes: true });
  });
  const drawn0 = await page.evaluate(() => window.anisomeshApp.state.meshesDrawn);
  for (let k = 1; k <= 6; k++) await page.mouse.move(h.x + 6 * k, h.y + 2 * k);
  // The moves' jobs run (at least one mesh drawn) while the handle is held.
  await page.waitForFunction((n) => window.anisomeshApp.state.meshesDrawn > n, drawn0, { timeout: 60000 });
  const held = await page.evaluate(() => {
    window.toolbarObserver.disconnect();
    return { changes: window.toolbarChanges, animation: getComputedStyle(document.querySelector('#status .spinner')).animationName };
  });
  assert.deepEqual(held, { changes: [], animation: 'none' });
  await page.mouse.up();
  await page.waitForFunction(() => window.anisomeshApp.state.dragToMeshMs !== null && window.anisomeshApp.idle(), null, { timeout: 60000 });
  assert.match(await page.locator('#status-text').textContent(), /^meshed in/);
  assert.deepEqual(errors, []);
  await page.close();
});

// ?threads=2 (an isolated page): each mesh worker loads 'anisomesh/threads' with a pool of one
// worker (loadAnisomesh({ threads: 2 })) and meshes on 2 threads; a drag there ends with the
// mesh the single-threaded module makes for the same input (loaded in the page itself).
test('with ?threads=2 the mesh worker runs 2 threads and a drag ends with the single-threaded module\'s mesh', async () => {
  const { page, errors } = await openSurfaceDragPage(env.browser, `${env.url}?threads=2`);
  assert.equal(await page.evaluate(() => window.anisomeshApp.meshRunner.threads), 2);
  await dragSourceOnce(page, 0);
  await settle(page);
  await page.evaluate(`window.meshDigestOf = ${meshDigest}`);
  const [shown, single] = await page.evaluate(async () => {
    const { loadAnisomesh } = await import('/wasm/browser.js');
    const am = await loadAnisomesh();
    const r = am.meshCase(JSON.stringify(window.anisomeshApp.state.case), { stats: false });
    const digests = [window.meshDigestOf(), window.meshDigestOf(r.mesh)];
    r.dispose?.();
    return digests;
  });
  assert.deepEqual(single, shown);
  assert.deepEqual(errors, []);
  await page.close();
});

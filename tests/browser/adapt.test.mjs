// The page's adaptation mode in headless Chromium: typing a function and running three
// iterations gives a mesh refined along the function's layer, drawn coloured by the field,
// with one table row per iteration; a bad expression is an error in the box, and the last
// mesh stays.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { launch, openPage, settle } from './launch.mjs';

let env;
before(async () => { env = await launch(); });
after(async () => { await env?.close(); });

const square = { domain: { outer: [{ type: 'polyline', points: [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]] }] }, controlSpace: { hmax: 0.05 } };

// Share of the vertices of the mesh on screen with |x + y - 1| < 0.1 (the layer of
// tanh(30 (x + y - 1)); the band is 19% of the square).
const nearLayer = () => {
  const m = window.anisomeshApp.views.mesh;
  let near = 0;
  const n = m.params.length / 2;
  for (let i = 0; i < n; i++) if (Math.abs(m.params[2 * i] + m.params[2 * i + 1] - 1) < 0.1) near++;
  return { near: near / n, vertices: n };
};

test('adaptation mode: three iterations refine along the typed function\'s layer', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  await settle(page, (c) => window.anisomeshApp.loadCaseText(c), JSON.stringify(square));
  const before = await page.evaluate(nearLayer);
  assert.ok(before.near < 0.3, `uniform mesh: ${before.near} of the vertices near the layer`);

  await page.locator('#adapt-box summary').click();
  await page.locator('#adapt-expr').fill('tanh(30*(x+y-1))');
  await page.locator('#adapt-value').fill('1500');
  await page.locator('#adapt-iterations').fill('3');
  await page.locator('#adapt-run').click();
  await page.waitForFunction(() => window.anisomeshApp.adapt.state.runs === 1 && !window.anisomeshApp.adapt.state.running, null, { timeout: 60000 });
  await settle(page);

  const r = await page.evaluate(() => {
    const a = window.anisomeshApp;
    return {
      iterations: a.adapt.state.iterations,
      error: a.adapt.state.error,
      rows: document.querySelectorAll('#adapt-table tr').length,
      colorBy: a.state.view.colorBy,
      drawn: a.views.mesh.triangles.length / 3,
      statTriangles: document.querySelector('#stats dd[data-key="triangles"]').textContent,
      status: document.getElementById('status-text').textContent,
    };
  });
  assert.equal(r.error, null);
  assert.equal(r.iterations.length, 3);
  assert.equal(r.rows, 4, 'a header and one row per iteration');
  assert.equal(r.colorBy, 'field');
  const last = r.iterations[2];
  assert.equal(r.drawn, last.triangles);
  assert.equal(r.statTriangles, String(last.triangles));
  assert.ok(Math.abs(last.vertices - 1500) < 225, `${last.vertices} vertices for N = 1500`);
  assert.ok(last.errorL2 > 0 && last.errorL2 < r.iterations[0].errorL2 * 1.5, JSON.stringify(r.iterations));
  assert.match(r.status, /iteration 3 of 3/);
  const after = await page.evaluate(nearLayer);
  assert.ok(after.near > 0.5, `adapted: ${after.near} of ${after.vertices} vertices near the layer`);
  // The faces are coloured by the field: the 2D view is not one plain colour.
  assert.ok(await page.evaluate(() => window.anisomeshApp.coverage('2d')) > 0.05);

  // A bad expression: a coded error in the box, the adapted mesh stays.
  await page.locator('#adapt-expr').fill('tanh(30*(x+y-1)');
  await page.locator('#adapt-iterations').fill('1');
  await page.locator('#adapt-run').click();
  await page.waitForFunction(() => window.anisomeshApp.adapt.state.runs === 2 && !window.anisomeshApp.adapt.state.running, null, { timeout: 60000 });
  const bad = await page.evaluate(() => ({
    text: document.getElementById('error-adapt').textContent,
    hidden: document.getElementById('error-adapt').hidden,
    drawn: window.anisomeshApp.views.mesh.triangles.length / 3,
  }));
  assert.equal(bad.hidden, false);
  assert.match(bad.text, /^PARSE_ERROR: /);
  assert.equal(bad.drawn, last.triangles, 'the last mesh stays on screen');

  // Back to the case: the case's own mesh, faces by quality again.
  await settle(page, () => document.getElementById('adapt-reset').click());
  const back = await page.evaluate(() => ({ colorBy: window.anisomeshApp.state.view.colorBy, near: 0 }));
  assert.equal(back.colorBy, 'quality');
  assert.ok((await page.evaluate(nearLayer)).near < 0.3);
  assert.deepEqual(errors, []);
  await page.close();
});

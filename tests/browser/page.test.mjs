// The demo page in headless Chromium: loads, the wasm core answers from the worker,
// the canvas shows the ellipses, and no page error happens.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { launch, openPage } from './launch.mjs';

let env;
before(async () => { env = await launch(); });
after(async () => { await env?.close(); });

test('page loads, the worker answers and the canvas is not blank', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  const version = await page.locator('#core-version').textContent();
  assert.match(version, /^\d+\.\d+\.\d+$/);
  const coverage = await page.evaluate(() => window.anisomeshDemo.canvasCoverage());
  assert.ok(coverage > 0.01, `canvas coverage ${coverage} should show the ellipses`);
  // The intersection shown equals the smaller input where M1 is inside M2 in every direction.
  const r = await page.evaluate(async () => {
    const d = window.anisomeshDemo;
    Object.assign(d.params.m1, { alphaDeg: 0, h1: 0.2, h2: 0.4 });
    Object.assign(d.params.m2, { alphaDeg: 0, h1: 0.5, h2: 0.9 });
    await d.update();
    return d.state.intersection;
  });
  assert.ok(Math.abs(r.h1 - 0.2) < 1e-9 && Math.abs(r.h2 - 0.4) < 1e-9, JSON.stringify(r));
  assert.equal(await page.locator('#stat-h1').textContent(), '0.2000');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a bad metric from the worker becomes an inline error and the page keeps working', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  const err = await page.evaluate(() =>
    window.anisomeshDemo.call('ellipses', { a: { h1: 0, h2: 1 }, b: { h: 1 } }).then(() => null, (e) => ({ code: e.code, message: e.message })));
  assert.equal(err.code, 'INVALID_METRIC');
  assert.match(err.message, /h1/);
  const after = await page.evaluate(async () => {
    const d = window.anisomeshDemo;
    const before = d.state.updates;
    await d.update();
    return d.state.updates - before;
  });
  assert.equal(after, 1);
  assert.deepEqual(errors, []);
  await page.close();
});

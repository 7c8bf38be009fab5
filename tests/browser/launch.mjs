// Shared setup for browser tests: Debian's Chromium, headless, software WebGL, and the
// demo server on a free loopback port. Never downloads a browser.
import { chromium } from 'playwright-core';
import { startServer } from '../../web/serve.mjs';
import { dragSource } from './fixtures.mjs';

export const chromiumArgs = [
  '--no-sandbox',
  '--enable-unsafe-swiftshader',
  '--use-angle=swiftshader',
  '--ignore-gpu-blocklist',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
  '--disable-quic',
];

/** Starts the server and the browser; returns { browser, url, close }. */
export async function launch() {
  const { server, url } = await startServer({ port: 0 });
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium',
    headless: true,
    args: chromiumArgs,
  });
  return {
    browser,
    url,
    async close() {
      await browser.close();
      await new Promise((r) => server.close(r));
    },
  };
}

/** Opens the app (optionally at a hash) and collects page errors and console errors. */
export async function openPage(browser, url, { hash = '', acceptDownloads = false } = {}) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 }, acceptDownloads });
  const errors = [];
  page.on('pageerror', (e) => errors.push(`pageerror: ${e.message}`));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  await page.goto(url + hash);
  await page.waitForFunction(() => window.anisomeshApp?.state.ready === true, null, { timeout: 30000 });
  return { page, errors };
}

/** Runs fn in the page, then waits until the app has no edit waiting and no job running. */
export async function settle(page, fn = null, arg = undefined) {
  if (fn) await page.evaluate(fn, arg);
  await page.waitForFunction(() => window.anisomeshApp.idle(), null, { timeout: 60000 });
}

// A page on the "p2 with holes" surface preset with one radial source selected (the
// surface drag of issue #12), the case's metric first changed by edit when given.
export async function openSurfaceDragPage(browser, url, edit = null) {
  const opened = await openPage(browser, url);
  await settle(opened.page, () => window.anisomeshApp.loadPreset('p2-holes'));
  await settle(opened.page, ({ e, source }) => {
    const a = window.anisomeshApp;
    if (e) Object.assign(a.state.case.metric, e);
    a.state.case.patches[0].sources = [source];
    a.state.selected = 0;
    a.edited(0);
  }, { e: edit, source: dragSource(0) });
  return opened;
}

// One drag of the selected source's centre handle (6 mouse moves, then release); resolves
// when the released drag's mesh is drawn and the page is idle.
export async function dragSourceOnce(page, rep) {
  const h = await page.evaluate(() => window.anisomeshApp.handleClientPosition(0, 'center'));
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  const dir = rep % 2 ? 1 : -1;
  for (let k = 1; k <= 6; k++) await page.mouse.move(h.x + dir * 6 * k, h.y + 2 * k);
  await page.evaluate(() => { window.anisomeshApp.state.dragToMeshMs = null; });
  await page.mouse.up();
  await page.waitForFunction(() => window.anisomeshApp.state.dragToMeshMs !== null && window.anisomeshApp.idle(), null, { timeout: 60000 });
}

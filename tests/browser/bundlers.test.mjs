// The package loads unchanged under Vite, esbuild (ESM and IIFE output), webpack and a plain
// <script type="module"> from a static folder: each builds a tiny page that imports
// 'anisomesh', meshes a case, and reports to the test from headless Chromium. The page also
// checks that a failed load (a wasm URL answering 404) throws AnisomeshError
// WASM_LOAD_FAILED and that the next loadAnisomesh() call succeeds (no cached failure).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, mkdirSync, writeFileSync, symlinkSync, rmSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { chromiumArgs } from './launch.mjs';
import { serveFolder } from './static-server.mjs';

const root = fileURLToPath(new URL('../..', import.meta.url));
const caseJson = readFileSync(join(root, 'examples/point_source.json'), 'utf8');

// The page's script: the same for every bundler.
const mainJs = (importFrom) => `
import { loadAnisomesh, AnisomeshError } from '${importFrom}';
const caseData = ${caseJson};
async function run() {
  const out = {};
  try {
    await loadAnisomesh({ wasmUrl: new URL('missing.wasm', location.href).href });
    out.failed = 'no error';
  } catch (e) {
    out.failed = e instanceof AnisomeshError ? e.code : 'not an AnisomeshError: ' + e;
  }
  const am = await loadAnisomesh();
  const { stats } = am.meshCase(caseData);
  out.version = am.version;
  out.triangles = stats.triangles;
  out.inverted = stats.inverted;
  return out;
}
run().then((r) => { window.result = r; }, (e) => { window.result = { error: String(e && e.stack || e) }; });
`;

let dir, browser;
before(async () => {
  dir = mkdtempSync(join(tmpdir(), 'anisomesh-bundlers-'));
  mkdirSync(join(dir, 'node_modules'));
  symlinkSync(root, join(dir, 'node_modules/anisomesh'), 'dir');
  writeFileSync(join(dir, 'main.js'), mainJs('anisomesh'));
  browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', headless: true, args: chromiumArgs });
});
after(async () => {
  await browser?.close();
  if (dir) rmSync(dir, { recursive: true, force: true });
});

const page = (script) => `<!doctype html><meta charset="utf-8"><title>anisomesh</title><script ${script}></script>`;

// Serves folder, opens index.html and returns what the page's script reported.
async function runPage(folder) {
  const server = await serveFolder(folder);
  const tab = await browser.newPage();
  const errors = [];
  tab.on('pageerror', (e) => errors.push(e.message));
  try {
    await tab.goto(`${server.url}/index.html`);
    await tab.waitForFunction(() => window.result !== undefined, null, { timeout: 60000 });
    return { result: await tab.evaluate(() => window.result), requests: server.requests, errors };
  } finally {
    await tab.close();
    await server.close();
  }
}

function checkResult({ result, errors }) {
  assert.equal(result.error, undefined, result.error);
  assert.equal(result.failed, 'WASM_LOAD_FAILED');
  assert.match(result.version, /^\d+\.\d+\.\d+/);
  assert.ok(result.triangles > 100, JSON.stringify(result));
  assert.equal(result.inverted, 0);
  assert.deepEqual(errors, []);
}

test('Vite build', { timeout: 180000 }, async () => {
  const { build } = await import('vite');
  writeFileSync(join(dir, 'index.html'), page('type="module" src="./main.js"'));
  await build({ root: dir, logLevel: 'silent', configFile: false, build: { outDir: join(dir, 'out-vite'), emptyOutDir: true } });
  const r = await runPage(join(dir, 'out-vite'));
  checkResult(r);
  assert.ok(r.requests.some((p) => p.endsWith('.wasm') && !p.includes('missing')), `no .wasm asset fetched: ${r.requests}`);
});

for (const format of ['esm', 'iife']) {
  test(`esbuild bundle (${format})`, { timeout: 120000 }, async () => {
    const esbuild = await import('esbuild');
    const out = join(dir, `out-esbuild-${format}`);
    await esbuild.build({ entryPoints: [join(dir, 'main.js')], bundle: true, format, outfile: join(out, 'main.js'), logLevel: 'silent' });
    writeFileSync(join(out, 'index.html'), page(`${format === 'esm' ? 'type="module" ' : ''}src="./main.js"`));
    checkResult(await runPage(out));
  });
}

test('webpack build', { timeout: 180000 }, async () => {
  const { default: webpack } = await import('webpack');
  const out = join(dir, 'out-webpack');
  const stats = await new Promise((resolve, reject) => {
    webpack({ mode: 'production', context: dir, entry: './main.js', output: { path: out, filename: 'main.js' }, performance: { hints: false } },
      (err, s) => (err ? reject(err) : resolve(s)));
  });
  assert.ok(!stats.hasErrors(), stats.toString('errors-only'));
  writeFileSync(join(out, 'index.html'), page('src="./main.js"'));
  const r = await runPage(out);
  checkResult(r);
  assert.ok(r.requests.some((p) => p.endsWith('.wasm') && !p.includes('missing')), `no .wasm asset fetched: ${r.requests}`);
});

test('plain <script type="module"> from a static folder', { timeout: 60000 }, async () => {
  const out = join(dir, 'out-static');
  mkdirSync(out, { recursive: true });
  symlinkSync(join(root, 'wasm'), join(out, 'anisomesh'), 'dir');
  writeFileSync(join(out, 'main.js'), mainJs('./anisomesh/browser.js'));
  writeFileSync(join(out, 'index.html'), page('type="module" src="./main.js"'));
  const r = await runPage(out);
  checkResult(r);
  assert.ok(r.requests.includes('/anisomesh/dist/anisomesh-core.wasm'), `${r.requests}`);
});

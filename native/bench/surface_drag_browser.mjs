#!/usr/bin/env node
// The surface drag benchmark (native/bench/surface_drag.mjs) run in headless Chromium's
// Web Worker beside the same runs in this Node process, to compare the two engines on the
// page worker's call (meshCase with measures and patch parameters, stats: false;
// elementMeasures: false as while a handle is held). Each run gives wall ms and the CPU
// time of the thread that ran it (/proc schedstat: the worker thread, Node's main thread),
// so a loaded machine still compares. The worker gets the module as the page gives it
// (compiled on the page with compileStreaming, posted), or compiles it itself (--self).
//
// Usage: node native/bench/surface_drag_browser.mjs [--runs N] [--self] [--node-only|--browser-only]
//   CHROMIUM_JS_FLAGS="--no-liftoff" ... passes V8 flags to Chromium (e.g. to see tiering).
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { chromiumArgs } from '../../tests/browser/launch.mjs';
import { startServer } from '../../web/serve.mjs';
import { wrapCore } from '../../wasm/api.js';
import { surfaceDragCases } from './surface_drag_cases.mjs';

const root = fileURLToPath(new URL('../..', import.meta.url));
const args = process.argv.slice(2);
const opt = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const runs = Number(opt('--runs', 8));
const selfCompile = args.includes('--self');
const dist = join(root, 'wasm/dist');

const cases = surfaceDragCases(root);
const options = { measures: true, elementMeasures: false, stats: false, patchParams: true };

// CPU ns of threads from /proc (schedstat's first field: time on the CPU).
const threadNs = (pid, tid) => Number(readFileSync(`/proc/${pid}/task/${tid}/schedstat`, 'utf8').split(' ')[0]);
function chromiumWorkerThreads() {
  const out = [];
  for (const pid of readdirSync('/proc').filter((d) => /^\d+$/.test(d))) {
    let cmd;
    try { cmd = readFileSync(`/proc/${pid}/cmdline`, 'utf8'); } catch { continue; }
    if (!cmd.includes('--type=renderer')) continue;
    for (const tid of readdirSync(`/proc/${pid}/task`)) {
      try {
        if (readFileSync(`/proc/${pid}/task/${tid}/comm`, 'utf8').startsWith('DedicatedWorker')) out.push([pid, tid]);
      } catch { /* gone */ }
    }
  }
  return out;
}
const sumNs = (threads) => threads.reduce((s, [p, t]) => { try { return s + threadNs(p, t); } catch { return s; } }, 0);

const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
const line = (name, tag, samples) => {
  const later = samples.slice(1);
  const f = (s) => `${s.cpu.toFixed(0)} (${s.wall.toFixed(0)})`;
  console.log(`${name.padEnd(30)} ${tag.padEnd(16)} ${String(samples[0].tris).padStart(6)}  first ${f(samples[0]).padEnd(11)}` +
    ` later median ${median(later.map((s) => s.cpu)).toFixed(0)} (${median(later.map((s) => s.wall)).toFixed(0)})` +
    `  best ${Math.min(...later.map((s) => s.cpu)).toFixed(0)}   cpu: ${later.map((s) => s.cpu.toFixed(0)).join(' ')}`);
};
console.log(`runs ${runs}: CPU (wall) ms of the thread that meshed; "later" = the runs after the first, the source moved each time`);

if (!args.includes('--browser-only')) {
  const { default: create } = await import(join(dist, 'anisomesh-core.js'));
  const am = wrapCore(await create({ wasmBinary: readFileSync(join(dist, 'anisomesh-core.wasm')) }));
  for (const [name, make] of cases) {
    const samples = [];
    for (let k = 0; k < runs; k++) {
      const c = make(k), n0 = threadNs(process.pid, process.pid), t0 = performance.now();
      const r = am.meshCase(c, options);
      samples.push({ cpu: (threadNs(process.pid, process.pid) - n0) / 1e6, wall: performance.now() - t0, tris: r.mesh.triangles.length / 3 });
      r.dispose?.();
    }
    line(name, `node ${process.versions.v8.split('-')[0]}`, samples);
  }
}

if (!args.includes('--node-only')) {
  const { server, url } = await startServer({ port: 0 });
  const jsFlags = process.env.CHROMIUM_JS_FLAGS;
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', headless: true,
    args: [...chromiumArgs, ...(jsFlags ? [`--js-flags=${jsFlags}`] : [])],
  });
  try {
    const page = await browser.newPage();
    const base = url.replace(/web\/$/, '');
    await page.goto(base + 'web/measure.js');  // any same-origin page without workers of its own
    const before = new Set(chromiumWorkerThreads().map(([, t]) => t));
    await page.evaluate(async ({ base, selfCompile }) => {
      const src = `
        let am = null;
        onmessage = async ({ data }) => {
          if (data.type === 'init') {
            const { default: create } = await import('${base}wasm/dist/anisomesh-core.js');
            const { wrapCore } = await import('${base}wasm/api.js');
            const opts = data.module
              ? { instantiateWasm(imports, done) { WebAssembly.instantiate(data.module, imports).then((i) => done(i, data.module)); return {}; } }
              : { locateFile: () => '${base}wasm/dist/anisomesh-core.wasm' };
            am = wrapCore(await create(opts));
            postMessage({ ready: true });
          } else {
            const t0 = performance.now();
            const r = am.meshCase(data.case, data.options);
            const wall = performance.now() - t0;
            r.dispose?.();
            postMessage({ wall, tris: r.mesh.triangles.length / 3 });
          }
        };`;
      const w = new Worker(URL.createObjectURL(new Blob([src], { type: 'text/javascript' })), { type: 'module' });
      window.benchWorker = w;
      const module = selfCompile ? null : await WebAssembly.compileStreaming(fetch(`${base}wasm/dist/anisomesh-core.wasm`));
      await new Promise((resolve) => { w.onmessage = resolve; w.postMessage({ type: 'init', module }); });
    }, { base, selfCompile });
    const threads = chromiumWorkerThreads().filter(([, t]) => !before.has(t));
    for (const [name, make] of cases) {
      const samples = [];
      for (let k = 0; k < runs; k++) {
        const n0 = sumNs(threads);
        const r = await page.evaluate(({ c, options }) => new Promise((resolve) => {
          window.benchWorker.onmessage = ({ data }) => resolve(data);
          window.benchWorker.postMessage({ type: 'run', case: c, options });
        }), { c: make(k), options });
        samples.push({ cpu: (sumNs(threads) - n0) / 1e6, wall: r.wall, tris: r.tris });
      }
      line(name, `chromium worker${selfCompile ? ' (self)' : ''}${jsFlags ? ' ' + jsFlags : ''}`, samples);
    }
  } finally {
    await browser.close();
    await new Promise((r) => server.close(r));
  }
}

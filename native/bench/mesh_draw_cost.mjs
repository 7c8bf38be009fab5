#!/usr/bin/env node
// What one draw of a mesh costs the GPU process in headless Chromium (software WebGL:
// SwiftShader, on the cores the mesh workers use): the page on "Surface p2 with holes"
// refined (chord tolerance 0.0025, hmax 0.3: ~53k triangles, ~80k edges) with a radial
// source, then repeated synchronous draws (a 1-pixel read back waits for the GPU) of the 2D
// view's mesh layers (faces + edges by length / plain / faces only) and of the 3D view
// (faces + plain edges / faces only); the GPU process's CPU ms per draw, medians of
// --rounds rounds of --draws draws. A measurement, no assertion.
//
// Usage: node native/bench/mesh_draw_cost.mjs [--root DIR] [--draws N] [--rounds N] [--only small|refined]
//   --root: the checkout whose page is served (default: this one), e.g. a base build to compare.
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';
import { chromiumCpuMs } from './chromium_cpu.mjs';
import { chromiumArgs, openSurfaceDragPage } from '../../tests/browser/launch.mjs';
import { refinedP2Metric } from '../../tests/browser/fixtures.mjs';

const args = process.argv.slice(2);
const opt = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const root = resolve(opt('--root', new URL('../..', import.meta.url).pathname));
const draws = Number(opt('--draws', 8)), rounds = Number(opt('--rounds', 3));
const only = opt('--only', 'refined');
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];

// CPU ms of the GPU process, all threads.
const gpuCpuMs = () => chromiumCpuMs('gpu-process');

const { startServer } = await import(pathToFileURL(`${root}/web/serve.mjs`).href);
const { server, url } = await startServer({ port: 0 });
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', headless: true, args: chromiumArgs });
try {
  const { page, errors } = await openSurfaceDragPage(browser, url, only === 'refined' ? refinedP2Metric : null);
  await page.evaluate(() => new Promise((r) => setTimeout(r, 1000)));
  const info = await page.evaluate(() => ({ tris: window.anisomeshApp.views.mesh.triangles.length / 3, mode: window.anisomeshApp.state.view.view }));
  console.log(`root ${root}: ${info.tris} triangles, view ${info.mode}; GPU-process CPU ms per draw (median of ${rounds} rounds of ${draws} draws)`);
  const kinds = [['2D faces + edges (length)', '2d', 'length'], ['2D faces + edges (plain)', '2d', 'plain'], ['2D faces only', '2d', 'off'], ['3D faces + edges (plain)', '3d', 'plain'], ['3D faces only', '3d', 'off']];
  const per = Object.fromEntries(kinds.map(([k]) => [k, []]));
  for (let r = 0; r < rounds; r++) {
    for (const [label, view, edges] of kinds) {
      await page.evaluate((e) => window.anisomeshApp.setView({ edges: e }), edges);
      await page.evaluate(() => new Promise((res) => setTimeout(res, 200)));
      const g0 = gpuCpuMs();
      await page.evaluate(({ view, draws }) => {
        const v = window.anisomeshApp.views;
        for (let i = 0; i < draws; i++) {
          v.invalidate2D();
          v.renderNow([view], { sync: true });
        }
      }, { view, draws });
      await page.evaluate(() => new Promise((res) => setTimeout(res, 100)));
      per[label].push((gpuCpuMs() - g0) / draws);
    }
  }
  for (const [label] of kinds) console.log(label.padEnd(28), median(per[label]).toFixed(1).padStart(7), '  rounds:', per[label].map((x) => x.toFixed(0)).join(' '));
  if (errors.length) console.log('page errors:', errors);
} finally {
  await browser.close();
  await new Promise((r) => server.close(r));
}

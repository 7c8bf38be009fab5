#!/usr/bin/env node
// What one WebGL frame costs the GPU process in headless Chromium (tests/browser/launch.mjs's
// flags: SwiftShader): CPU ms per frame of a canvas that clears a 10 x 10 pixel corner each
// animation frame, for a few canvas sizes and context attributes. On a machine without a GPU
// this is CPU the page's frames take from the mesh workers, whatever the frame draws (why
// the page draws a dragged handle outside WebGL, web/views.js). A measurement, no assertion.
//
// Usage: node native/bench/webgl_frame_cost.mjs [--frames N]
//   CHROMIUM_EXTRA_ARGS="--disable-gpu-compositing" adds Chromium flags.
import { chromium } from 'playwright-core';
import { chromiumCpuMs } from './chromium_cpu.mjs';
import { chromiumArgs } from '../../tests/browser/launch.mjs';
import { startServer } from '../../web/serve.mjs';

const args = process.argv.slice(2);
const frames = Number(args.includes('--frames') ? args[args.indexOf('--frames') + 1] : 30);

// CPU ms of the GPU process, all threads.
const gpuCpuMs = () => chromiumCpuMs('gpu-process');

const extra = process.env.CHROMIUM_EXTRA_ARGS?.split(' ').filter(Boolean) ?? [];
const { server, url } = await startServer({ port: 0 });
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', headless: true, args: [...chromiumArgs, ...extra] });
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await page.goto(`${url}web/index.html`);
  await page.evaluate(() => new Promise((r) => setTimeout(r, 1500)));
  console.log(`flags: ${[...chromiumArgs, ...extra].join(' ')}`);
  console.log('canvas'.padEnd(10), 'preserveDrawingBuffer', 'antialias', 'GPU-process CPU ms per frame');
  for (const [w, h, preserve, aa] of [[0, 0, false, false], [940, 603, true, false], [940, 603, false, false], [200, 100, true, false], [940, 603, true, true]]) {
    const g0 = gpuCpuMs();
    await page.evaluate(async ({ w, h, preserve, aa, frames }) => {
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      if (!w) {  // no canvas: a frame of the page's compositor alone (a CSS transform changes)
        const d = document.createElement('div');
        d.style.cssText = 'position:fixed;left:0;top:0;width:20px;height:20px;background:#c00;z-index:99';
        document.body.appendChild(d);
        for (let i = 0; i < frames; i++) { d.style.transform = `translateX(${i % 7}px)`; await frame(); }
        d.remove();
        return;
      }
      const c = document.createElement('canvas');
      c.width = w; c.height = h;
      c.style.cssText = 'position:fixed;left:0;top:0;z-index:99';
      document.body.appendChild(c);
      const gl = c.getContext('webgl2', { preserveDrawingBuffer: preserve, antialias: aa });
      gl.enable(gl.SCISSOR_TEST);
      gl.scissor(0, 0, 10, 10);
      for (let i = 0; i < frames; i++) {
        gl.clearColor(i / frames, 0, 0, 1);
        gl.clear(gl.COLOR_BUFFER_BIT);
        await frame();
      }
      c.remove();
    }, { w, h, preserve, aa, frames });
    const label = w ? `${w}x${h}` : 'no WebGL';
    console.log(label.padEnd(10), String(w ? preserve : '-').padStart(21), String(w ? aa : '-').padStart(9), ((gpuCpuMs() - g0) / frames).toFixed(1).padStart(28));
  }
} finally {
  await browser.close();
  await new Promise((r) => server.close(r));
}

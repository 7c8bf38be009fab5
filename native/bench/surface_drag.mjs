#!/usr/bin/env node
// Surface drag benchmark: the page worker's meshCase call (measures and patch parameters,
// stats: false; the report, which makes the chord deviations, follows the drawn mesh:
// timed apart, as the page asks for it) on "Surface p2 with holes" with a radial source, as is (~5.8k triangles)
// and refined (chord tolerance 0.0025, hmax 0.3: ~53k), and on every surface example,
// in one wasm instance: the first run, then runs with the source moved as a drag moves
// it (the core keeps each patch's curvature stage between them). Prints process CPU and
// wall ms per run kind (best of the drag runs), so a loaded machine still gives usable
// figures. A different build (e.g. a saved wasm/dist) can be named for a before/after.
//
// Usage: node native/bench/surface_drag.mjs [--dist DIR] [--runs N]
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { wrapCore } from '../../wasm/api.js';
import { surfaceDragCases } from './surface_drag_cases.mjs';

const root = fileURLToPath(new URL('../..', import.meta.url));
const args = process.argv.slice(2);
const opt = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const dist = opt('--dist', join(root, 'wasm/dist'));
const runs = Number(opt('--runs', 4));
const { default: create } = await import(join(dist, 'anisomesh-core.js'));
const am = wrapCore(await create({ wasmBinary: readFileSync(join(dist, 'anisomesh-core.wasm')) }));

const surfaceDir = join(root, 'examples/surface');
const cases = [
  ...surfaceDragCases(root),
  ...readdirSync(surfaceDir).filter((f) => f.endsWith('.json')).sort().map((f) => {
    const c = JSON.parse(readFileSync(join(surfaceDir, f), 'utf8'));
    return [f, () => c];
  }),
];

const cpuMs = (c0) => { const d = process.cpuUsage(c0); return (d.user + d.system) / 1000; };
console.log(`wasm: ${dist}`);
console.log('case'.padEnd(34), 'triangles', 'first run CPU (wall) ms', 'later runs best CPU (wall) ms', 'report() after, CPU ms', 'dragging: best CPU ms');
for (const [name, make] of cases) {
  let first = null, best = null, tris = 0, report = null, drag = null;
  for (let k = 0; k < runs; k++) {
    const c = make(k);
    const c0 = process.cpuUsage(), t0 = performance.now();
    const r = am.meshCase(c, { measures: true, stats: false, patchParams: true });
    const sample = { cpu: cpuMs(c0), wall: performance.now() - t0 };
    tris = r.mesh.triangles.length / 3;
    if (k === 0) first = sample;
    else if (!best || sample.cpu < best.cpu) best = sample;
    // An older build gives the stats at once (no report()).
    const c1 = process.cpuUsage();
    if (r.report) r.report();
    const rep = r.report ? cpuMs(c1) : 0;
    if (k > 0 && (report === null || rep < report)) report = rep;
    // While a handle is held the worker leaves the per-element colours to the report too.
    const c2 = process.cpuUsage();
    const d = am.meshCase(make(k + 1), { measures: true, elementMeasures: false, stats: false, patchParams: true });
    const dragCpu = cpuMs(c2);
    d.dispose?.();
    if (k > 0 && (drag === null || dragCpu < drag)) drag = dragCpu;
  }
  const f = (s) => (s ? `${s.cpu.toFixed(0)} (${s.wall.toFixed(0)})` : '-');
  console.log(name.padEnd(34), String(tris).padStart(9), f(first).padStart(23), f(best).padStart(29), String(report?.toFixed(0) ?? '-').padStart(22), String(drag?.toFixed(0) ?? '-').padStart(21));
}

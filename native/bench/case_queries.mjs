#!/usr/bin/env node
// Metric queries per second through the npm package (WebAssembly in Node) on the control
// space of example cases, in batches (ControlSpace.metricsAt), next to the native figure
// of the same structure (Google Benchmark BM_CaseControlSpaceQuery, when built).
// Usage: node native/bench/case_queries.mjs
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadAnisomesh } from 'anisomesh';

const root = fileURLToPath(new URL('../..', import.meta.url));
const bench = join(root, 'build/native/bin/anisomesh_bench');
const am = await loadAnisomesh();

let native = {};
if (existsSync(bench)) {
  const out = execFileSync(bench, ['--benchmark_filter=BM_CaseControlSpaceQuery', '--benchmark_format=json', '--benchmark_min_time=0.3'], { encoding: 'utf8' });
  for (const b of JSON.parse(out).benchmarks) native[b.name.split('/')[1]] = b.items_per_second;
}

const rows = [];
for (const name of ['boundary_layer', 'shear_layer']) {
  const c = JSON.parse(readFileSync(join(root, `examples/${name}.json`), 'utf8'));
  const cs = am.createControlSpace(c);
  const { bounds } = cs.inspect();
  const [x0, y0] = bounds.lo, [x1, y1] = bounds.hi;
  const n = 1 << 16;
  const xy = new Float64Array(2 * n);
  let seed = 7;
  const rnd = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  for (let i = 0; i < n; i++) { xy[2 * i] = x0 + (x1 - x0) * rnd(); xy[2 * i + 1] = y0 + (y1 - y0) * rnd(); }
  cs.metricsAt(xy);  // warm up
  let queries = 0;
  const t0 = performance.now();
  while (performance.now() - t0 < 1000) { cs.metricsAt(xy); queries += n; }
  const wasm = queries / ((performance.now() - t0) / 1000);
  cs.dispose();
  rows.push([name, (wasm / 1e6).toFixed(1), native[name] ? (native[name] / 1e6).toFixed(1) : 'n/a', native[name] ? (native[name] / wasm).toFixed(2) : 'n/a']);
}
console.log('| case | wasm M queries/s (batches of 65536) | native M queries/s | native/wasm |');
console.log('|---|---|---|---|');
for (const r of rows) console.log(`| ${r.join(' | ')} |`);

#!/usr/bin/env node
// Whole-run benchmark: the same JSON cases meshed by the native CLI and by the npm
// package (WebAssembly in Node). Prints one table with the core's own stage times
// (measured inside C++ in both builds, best of N runs), their
// ratio, the wasm binary size (raw and gzip) and the module start-up time.
//
// Usage: node native/bench/wasm_vs_native.mjs [--runs N] [CASE.json ...]
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh');
const args = process.argv.slice(2);
let runs = 3;
const cases = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--runs') runs = Number(args[++i]);
  else cases.push(args[i]);
}

const t0 = performance.now();
const { loadAnisomesh } = await import('anisomesh');
const am = await loadAnisomesh();
const startup = performance.now() - t0;

const tmp = mkdtempSync(join(tmpdir(), 'anisomesh-wvn-'));
if (cases.length === 0) {
  // A larger variant of the point-source example (~100k triangles) next to the examples.
  const big = JSON.parse(readFileSync(join(root, 'examples/point_source.json'), 'utf8'));
  big.controlSpace.hmax = 0.01;
  big.sources[0].h0 = 0.001;
  writeFileSync(join(tmp, 'point_source_fine.json'), JSON.stringify(big));
  cases.push(...['boundary_layer', 'fig7_rect_holes_dr2', 'point_source'].map((n) => join(root, `examples/${n}.json`)),
    join(tmp, 'point_source_fine.json'));
}

// Stage times measured inside C++ (planar: pipelineSeconds; surface: secondsTotal).
const coreSeconds = (s) => (s.pipelineSeconds ? Object.values(s.pipelineSeconds).reduce((a, b) => a + b, 0) : s.secondsTotal);
const rows = [];
for (const file of cases) {
  const text = readFileSync(file, 'utf8');
  let native = Infinity, wasm = Infinity, triangles = 0;
  for (let r = 0; r < runs; r++) {
    const s = JSON.parse(execFileSync(cli, ['mesh', file, '-o', join(tmp, 'out.mesh'), '--stats'], { encoding: 'utf8' }));
    native = Math.min(native, coreSeconds(s));
    const w = am.meshCase(text).stats;
    wasm = Math.min(wasm, coreSeconds(w));
    triangles = w.triangles;
  }
  rows.push([basename(file, '.json'), String(triangles), (1000 * native).toFixed(1), (1000 * wasm).toFixed(1), (wasm / native).toFixed(2)]);
}
rmSync(tmp, { recursive: true, force: true });

const header = ['case', 'triangles', 'native ms', 'wasm ms', 'wasm/native'];
const widths = header.map((h, i) => Math.max(h.length, ...rows.map((r) => r[i].length)));
const line = (cells) => '| ' + cells.map((c, i) => c.padEnd(widths[i])).join(' | ') + ' |';
console.log(line(header));
console.log('|' + widths.map((w) => '-'.repeat(w + 2)).join('|') + '|');
for (const r of rows) console.log(line(r));
const wasmFile = join(root, 'wasm/dist/anisomesh-core.wasm');
const raw = statSync(wasmFile).size, gz = gzipSync(readFileSync(wasmFile), { level: 9 }).length;
console.log(`\nwasm binary: ${(raw / 1024).toFixed(0)} KiB, gzip ${(gz / 1024).toFixed(0)} KiB; module start-up (import + instantiate) ${startup.toFixed(0)} ms`);

#!/usr/bin/env node
// The same remesh case through the native CLI and through the npm package (WebAssembly in
// Node), issue #14's wasm / native ratio. Inputs: the directories remesh_throughput.mjs keeps
// (`--keep DIR --generate-only`: DIR/<case>/in.mesh + in.sol). For each case, best of --runs:
// native: the CLI process (`remesh in.mesh -sol in.sol -o out.mesh`, one thread), wall and CPU
// from /usr/bin/time; wasm: in this process readMesh + readSol (of the files' bytes) + remesh + writeMesh, wall and
// process CPU. Both outputs are compared (the same mesh text is expected: same input, same mesh).
//
// Usage: node native/bench/remesh_wasm_vs_native.mjs [--runs N] DIR/<case> ...
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join, resolve, basename } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createHash } from 'node:crypto';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = resolve(process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh'));
const args = process.argv.slice(2);
let runs = 3;
const dirs = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--runs') runs = Number(args[++i]);
  else dirs.push(args[i]);
}
if (dirs.length === 0) {
  console.error('usage: remesh_wasm_vs_native.mjs [--runs N] DIR ... (DIR holds in.mesh and in.sol)');
  process.exit(2);
}
const { loadAnisomesh } = await import('anisomesh');
const am = await loadAnisomesh();
const md5 = (s) => createHash('md5').update(s).digest('hex').slice(0, 12);

const rows = [];
for (const dir of dirs) {
  let native = null;
  for (let r = 0; r < runs; r++) {
    const p = spawnSync('/usr/bin/time', ['-f', 'TIME %e %U %S %M', cli, 'remesh', 'in.mesh', '-sol', 'in.sol', '-o', 'out.mesh', '-threads', '1'],
      { cwd: dir, encoding: 'utf8', maxBuffer: 1 << 28 });
    const line = (p.stderr || '').split('\n').find((l) => l.startsWith('TIME '));
    if (p.status !== 0 || !line) throw new Error(`CLI failed in ${dir}: ${p.stderr}`);
    const [wall, user, sys, rssKb] = line.split(' ').slice(1).map(Number);
    if (!native || user + sys < native.cpu) native = { wall, cpu: user + sys, rss: rssKb / 1024 };
  }
  const nativeOut = readFileSync(join(dir, 'out.mesh'), 'utf8');
  let wasm = null, wasmOut = '';
  for (let r = 0; r < runs; r++) {
    const c0 = process.cpuUsage(), t0 = performance.now();
    // The files' bytes, as the CLI reads them (decoding them into strings and encoding them
    // back took 3.1 of the 3.8 s the package spent reading the rotated 1e6 case).
    const mesh = am.readMesh(readFileSync(join(dir, 'in.mesh')));
    const metrics = am.readSol(readFileSync(join(dir, 'in.sol')), mesh.vertices.length / mesh.dimension);
    const t1 = performance.now();
    const out = am.remesh(mesh, metrics);
    const t2 = performance.now();
    wasmOut = am.writeMesh(out.mesh);
    const t3 = performance.now();
    const c = process.cpuUsage(c0);
    const cpu = (c.user + c.system) / 1e6;
    if (!wasm || cpu < wasm.cpu) {
      wasm = { wall: (t3 - t0) / 1e3, cpu, read: (t1 - t0) / 1e3, remesh: (t2 - t1) / 1e3, write: (t3 - t2) / 1e3,
        triangles: out.mesh.triangles.length / 3 };
    }
  }
  rows.push({ case: basename(dir), triangles: wasm.triangles, native, wasm, same: md5(nativeOut) === md5(wasmOut),
    hashes: [md5(nativeOut), md5(wasmOut)] });
  console.error(JSON.stringify(rows[rows.length - 1]));
}
const f = (x, d = 2) => x.toFixed(d);
console.log('| case | triangles | native wall / CPU s | wasm wall / CPU s (read, remesh, write wall) | wasm / native CPU | wasm / native wall | same mesh |');
console.log('|---|---|---|---|---|---|---|');
for (const r of rows) {
  console.log(`| ${r.case} | ${r.triangles} | ${f(r.native.wall)} / ${f(r.native.cpu)} | ${f(r.wasm.wall)} / ${f(r.wasm.cpu)} ` +
    `(${f(r.wasm.read)}, ${f(r.wasm.remesh)}, ${f(r.wasm.write)}) | ${f(r.wasm.cpu / r.native.cpu)} | ${f(r.wasm.wall / r.native.wall)} | ${r.same ? 'yes' : 'no ' + r.hashes.join(' vs ')} |`);
}

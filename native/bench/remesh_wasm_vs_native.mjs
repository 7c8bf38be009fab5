#!/usr/bin/env node
// The same remesh case through the native CLI and through the npm package (WebAssembly in
// Node), issue #14's wasm / native ratio. Inputs: the directories remesh_throughput.mjs keeps
// (`--keep DIR --generate-only`: DIR/<case>/in.mesh + in.sol). For each case, best of --runs:
// native: the CLI process (`remesh in.mesh -sol in.sol -o out.mesh`, one thread), wall and CPU
// from /usr/bin/time; wasm: in this process readMesh + readSol (of the files' bytes) + remesh + writeMesh, wall and
// process CPU. Both outputs are compared (the same mesh text is expected: same input, same mesh).
//
// The package's remesh is called with stats: false (no quality report: the CLI makes none
// without --stats).
// --stages: a second table, stage by stage, each stage's least over the runs (the least
// disturbed on a loaded machine): native from the CLI's -v 1 lines (process CPU), wasm from the
// CPU time of the thread running the module (/proc/thread-self/schedstat) around the package
// calls and at remesh's onStage marks: read (readMesh + readSol), input (the mesh and metrics
// into the core), the core's stages, output (the mesh out to JS), write (writeMesh).
//
// Usage: node native/bench/remesh_wasm_vs_native.mjs [--runs N] [--stages] [--out OUT] [--package DIR] DIR/<case> ...
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join, resolve, basename } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createHash } from 'node:crypto';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = resolve(process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh'));
const args = process.argv.slice(2);
let runs = 3, stages = false, outDir = null, pkgDir = null;
const dirs = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--runs') runs = Number(args[++i]);
  else if (args[i] === '--stages') stages = true;
  else if (args[i] === '--out') outDir = resolve(args[++i]);
  else if (args[i] === '--package') pkgDir = resolve(args[++i]);
  else dirs.push(args[i]);
}
if (dirs.length === 0) {
  console.error('usage: remesh_wasm_vs_native.mjs [--runs N] [--stages] [--out OUT] [--package DIR] DIR ... (DIR holds in.mesh and in.sol)');
  process.exit(2);
}
// --package DIR: another copy of the package (DIR/wasm/node.js), e.g. a baseline build.
const { loadAnisomesh } = await import(pkgDir ? pathToFileURL(join(pkgDir, 'wasm/node.js')).href : 'anisomesh');
const am = await loadAnisomesh();
const md5 = (s) => createHash('md5').update(s).digest('hex').slice(0, 12);

// CPU seconds of this thread (the one running the module; V8's compiler and GC threads are
// left out), from the scheduler's nanoseconds; wall time where there is no /proc.
const threadCpu = (() => {
  try {
    readFileSync('/proc/thread-self/schedstat', 'utf8');
    return () => Number(readFileSync('/proc/thread-self/schedstat', 'utf8').split(' ')[0]) / 1e9;
  } catch {
    return () => performance.now() / 1e3;
  }
})();
// Each stage's least value over the runs.
const least = (best, now) => {
  for (const [k, v] of Object.entries(now)) best[k] = typeof v === 'number' ? Math.min(best[k] ?? Infinity, v) : v;
  return best;
};
const rows = [];
for (const dir of dirs) {
  let native = null;
  const nativeStages = {};
  // The CLI's output: DIR/out.mesh, or OUT/<case>.mesh with --out OUT (input folders shared).
  const outFile = outDir ? join(outDir, `${basename(dir)}.mesh`) : join(dir, 'out.mesh');
  for (let r = 0; r < runs; r++) {
    const p = spawnSync('/usr/bin/time', ['-f', 'TIME %e %U %S %M', cli, 'remesh', 'in.mesh', '-sol', 'in.sol', '-o', outFile, '-threads', '1',
      ...(stages ? ['-v', '1'] : [])],
      { cwd: dir, encoding: 'utf8', maxBuffer: 1 << 28, env: { ...process.env, GLIBC_TUNABLES: 'glibc.malloc.hugetlb=0' } });
    const lines = (p.stderr || '').split('\n');
    const line = lines.find((l) => l.startsWith('TIME '));
    if (p.status !== 0 || !line) throw new Error(`CLI failed in ${dir}: ${p.stderr}`);
    const [wall, user, sys, rssKb] = line.split(' ').slice(1).map(Number);
    if (!native || user + sys < native.cpu) native = { wall, cpu: user + sys, rss: rssKb / 1024 };
    // anisomesh: stage control space  wall 0.908 s cpu 0.172 s ...
    const now = {};
    for (const l of lines) {
      const m = /^anisomesh: stage (.+?) +wall ([\d.]+) s cpu ([\d.]+) s/.exec(l);
      if (m) now[m[1]] = Number(m[3]);
    }
    least(nativeStages, now);
  }
  const nativeOut = readFileSync(outFile, 'utf8');
  let wasm = null, wasmOut = '';
  const wasmStages = {};
  for (let r = 0; r < runs; r++) {
    const c0 = process.cpuUsage(), t0 = performance.now(), k0 = threadCpu();
    // The files' bytes, as the CLI reads them (decoding them into strings and encoding them
    // back took 3.1 of the 3.8 s the package spent reading the rotated 1e6 case).
    const mesh = am.readMesh(readFileSync(join(dir, 'in.mesh')));
    const km = threadCpu();
    const metrics = am.readSol(readFileSync(join(dir, 'in.sol')), mesh.vertices.length / mesh.dimension);
    const t1 = performance.now(), k1 = threadCpu();
    // stats: false: no quality report (the CLI makes none without --stats); onStage marks the
    // core's stages (a package without these options ignores them).
    const marks = [];
    const out = am.remesh(mesh, metrics, { stats: false, onStage: (name) => marks.push([name, threadCpu()]) });
    out.dispose?.();
    const t2 = performance.now(), k2 = threadCpu();
    wasmOut = am.writeMesh(out.mesh);
    const t3 = performance.now(), k3 = threadCpu();
    const c = process.cpuUsage(c0);
    const cpu = (c.user + c.system) / 1e6;
    const now = { readMesh: km - k0, readSol: k1 - km, read: k1 - k0, remesh: k2 - k1, write: k3 - k2, total: k3 - k0 };
    if (marks.length > 0) {
      // From the call to the first stage: the mesh and metrics into the core.
      marks.unshift(['input', k1]);
      marks.push(['end', k2]);
      for (let i = 0; i + 1 < marks.length; i++) now[marks[i][0]] = (now[marks[i][0]] ?? 0) + marks[i + 1][1] - marks[i][1];
    } else {  // a package without onStage: the core's own stage times (wall: marked * in the table)
      const ps = out.stats.pipelineSeconds;
      Object.assign(now, { boundary: ps.geometry, 'control space': ps.controlSpace, discretization: ps.discretization + ps.boundaryUpdates,
        meshing: ps.meshing });
      wasmStages.wall = true;
    }
    least(wasmStages, now);
    if (!wasm || cpu < wasm.cpu) {
      wasm = { wall: (t3 - t0) / 1e3, cpu, read: (t1 - t0) / 1e3, remesh: (t2 - t1) / 1e3, write: (t3 - t2) / 1e3,
        triangles: out.mesh.triangles.length / 3 };
    }
  }
  rows.push({ case: basename(dir), triangles: wasm.triangles, native, wasm, nativeStages, wasmStages, same: md5(nativeOut) === md5(wasmOut),
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
if (stages) {
  const names = ['read', 'input', 'boundary', 'control space', 'discretization', 'meshing', 'output', 'write', 'total'];
  console.log('');
  console.log('Stages, least over the runs: native CPU s (-v 1) / wasm thread CPU s (ratio); wasm read = readMesh + readSol,');
  console.log('input: remesh() from its call to the core\'s first stage, output: from the core\'s end to its return;');
  console.log('total: the sum of the stages (native), the whole read + remesh + write (wasm); * wall times (a package without onStage)');
  for (const r of rows) r.nativeStages.total = Object.values(r.nativeStages).reduce((a, b) => a + b, 0);
  console.log(`| case | ${names.join(' | ')} |`);
  console.log(`|---|${names.map(() => '---').join('|')}|`);
  for (const r of rows) {
    const cells = names.map((n) => {
      const a = r.nativeStages[n] ?? 0, b = r.wasmStages[n] ?? 0;
      const wall = r.wasmStages.wall && ['boundary', 'control space', 'discretization', 'meshing'].includes(n) ? '*' : '';
      return `${f(a, 3)} / ${f(b, 3)}${wall}${a > 0 ? ` (${f(b / a)})` : ''}`;
    });
    console.log(`| ${r.case} | ${cells.join(' | ')} |`);
  }
}

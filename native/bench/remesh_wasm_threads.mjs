#!/usr/bin/env node
// The package's remesh (readMesh + readSol + remesh + writeMesh, as remesh_wasm_vs_native.mjs)
// through the single-threaded module ('anisomesh') and the pthreads module ('anisomesh/threads')
// at 1, 2 (and 3) threads, interleaved in one process: for each case, --runs rounds of every
// configuration in turn. Per configuration: median wall and median process CPU (process.cpuUsage:
// the module's thread, its workers, V8's threads), and the md5 of the output mesh text (the
// same for all is expected). Inputs: remesh_throughput.mjs --generate-only --keep DIR.
//
// A first round per case is not counted (V8 tiers the wasm code up during the first runs).
// main: CPU of the calling thread alone (on a loaded machine the workers may wait for a core:
// wall then exceeds what two free cores give, about max(main, the longest worker)).
// --square H: also meshCase of the unit square with hmax H (a planar case meshed as domain parts).
//
// Usage: node native/bench/remesh_wasm_threads.mjs [--runs N] [--threads 1,2] [--square H] DIR/<case> ...
import { readFileSync } from 'node:fs';
import { join, basename } from 'node:path';
import { createHash } from 'node:crypto';

const args = process.argv.slice(2);
let runs = 5, threads = [1, 2], square = null;
const dirs = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--runs') runs = Number(args[++i]);
  else if (args[i] === '--threads') threads = args[++i].split(',').map(Number);
  else if (args[i] === '--square') square = Number(args[++i]);
  else dirs.push(args[i]);
}
const st = await (await import('../../wasm/node.js')).loadAnisomesh();
const mt = await (await import('../../wasm/threads-node.js')).loadAnisomesh();
const configs = [{ name: 'st', am: st, threads: 1 }, ...threads.map((t) => ({ name: `mt-${t}`, am: mt, threads: t }))];
const md5 = (s) => createHash('md5').update(s).digest('hex').slice(0, 8);
const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];

// CPU seconds of the calling thread (the scheduler's nanoseconds).
const threadCpu = () => Number(readFileSync('/proc/thread-self/schedstat', 'utf8').split(' ')[0]) / 1e9;

function run(c, dir) {
  c.am.setThreads(c.threads);
  const u0 = process.cpuUsage(), t0 = performance.now(), k0 = threadCpu();
  let out;
  if (dir.startsWith('square:')) {
    const hmax = Number(dir.slice(7));
    out = c.am.meshCase({ domain: { outer: [{ type: 'polyline', points: [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]] }] }, controlSpace: { hmax } }, { stats: false });
  } else {
    const mesh = c.am.readMesh(readFileSync(join(dir, 'in.mesh')));
    const metrics = c.am.readSol(readFileSync(join(dir, 'in.sol')), mesh.vertices.length / mesh.dimension);
    out = c.am.remesh(mesh, metrics, { stats: false });
  }
  out.dispose?.();
  const text = c.am.writeMesh(out.mesh);
  const main = threadCpu() - k0;
  const u = process.cpuUsage(u0);
  return { wall: (performance.now() - t0) / 1e3, cpu: (u.user + u.system) / 1e6, main, md5: md5(text), triangles: out.mesh.triangles.length / 3 };
}
if (square !== null) dirs.unshift(`square:${square}`);

for (const dir of dirs) {
  const got = new Map(configs.map((c) => [c.name, []]));
  for (const c of configs) run(c, dir);
  for (let r = 0; r < runs; r++) for (const c of configs) got.get(c.name).push(run(c, dir));
  for (const c of configs) {
    const v = got.get(c.name);
    const hashes = [...new Set(v.map((x) => x.md5))].join(',');
    console.log(`${basename(dir)} ${c.name.padEnd(5)} triangles ${v[0].triangles} wall ${median(v.map((x) => x.wall)).toFixed(3)} s` +
      ` cpu ${median(v.map((x) => x.cpu)).toFixed(3)} s main ${median(v.map((x) => x.main)).toFixed(3)} s  (walls ${v.map((x) => x.wall.toFixed(2)).join(' ')})  md5 ${hashes}`);
  }
}

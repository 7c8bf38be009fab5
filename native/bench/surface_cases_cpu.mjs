#!/usr/bin/env node
// CPU time of `anisomesh mesh` on every surface example (issue #12's "native CPU time per
// surface case"), optionally beside another build (--baseline CLI, e.g. a worktree of an older
// commit), runs alternating between the two so that load changes hit both alike. Prints one
// table: median CPU ms (user + system of the child), page faults and peak RSS per case and CLI.
//
// Usage: node native/bench/surface_cases_cpu.mjs [--runs 7] [--baseline PATH/TO/anisomesh]
import { spawnSync } from 'node:child_process';
import { readdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const args = process.argv.slice(2);
const opt = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const runs = Number(opt('--runs', 7));
const clis = [['this build', resolve(process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh'))]];
if (opt('--baseline', null)) clis.unshift(['baseline', resolve(opt('--baseline'))]);
const dir = join(root, 'examples/surface');
const cases = readdirSync(dir).filter((f) => f.endsWith('.json')).sort();
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];

// One run: CPU seconds from bash's time (ms resolution; it includes GNU time's own ~1 ms),
// minor faults and peak RSS KiB from GNU time (whose CPU figures have 10 ms resolution).
function once(cli, file) {
  const out = join(tmpdir(), 'anisomesh-surface-bench.mesh');
  const script = `TIMEFORMAT='%3U %3S'; time /usr/bin/time -f '%R %M' "$0" mesh "$1" -o "$2" >/dev/null`;
  const r = spawnSync('bash', ['-c', script, cli, join(dir, file), out], { encoding: 'utf8' });
  const lines = r.stderr.trim().split('\n');
  const [faults, rssKiB] = lines.at(-2).split(' ').map(Number);
  const [user, sys] = lines.at(-1).split(' ').map(Number);
  if (r.status !== 0 || !Number.isFinite(faults) || !Number.isFinite(user)) throw new Error(`${cli} ${file}: ${r.stderr}`);
  return { cpuMs: 1000 * (user + sys), faults, rssMiB: rssKiB / 1024 };
}

const rows = new Map();
for (let k = 0; k < runs; k++)
  for (const file of cases)
    for (const [name, cli] of clis) {
      const key = `${file}\t${name}`;
      if (!rows.has(key)) rows.set(key, []);
      rows.get(key).push(once(cli, file));
    }

console.log(`median of ${runs} runs (alternating): CPU ms = user + system of the CLI process; faults = minor page faults`);
console.log('| case | CLI | CPU ms | faults | peak RSS MiB |');
console.log('|---|---|---|---|---|');
for (const [key, list] of rows) {
  const [file, name] = key.split('\t');
  console.log(`| ${file} | ${name} | ${median(list.map((x) => x.cpuMs)).toFixed(1)} | ${median(list.map((x) => x.faults))} | ${median(list.map((x) => x.rssMiB)).toFixed(1)} |`);
}

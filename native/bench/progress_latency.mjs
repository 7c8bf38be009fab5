#!/usr/bin/env node
// Cancellation latency of hostile cases through the npm package (issue #15): with an
// always-false onProgress, the time from the call to the first callback and from that
// callback to the CANCELLED throw; with an always-true one, the callbacks' largest gap
// (every stage must report), the run's end (its code) and, cancelling at the first
// callback after half of that run, the callback-to-throw time late in the run. Wall and
// CPU milliseconds (process.cpuUsage, the whole process) beside each other.
//   node native/bench/progress_latency.mjs [--repeat 3]
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { loadAnisomesh, AnisomeshError } from 'anisomesh';

const root = fileURLToPath(new URL('../..', import.meta.url));
const repeat = Number(process.argv[process.argv.indexOf('--repeat') + 1] || 1) || 1;
const am = await loadAnisomesh();
const file = (name) => readFileSync(`${root}tests/bad_input/${name}`, 'utf8');
const square = { outer: [{ type: 'polyline', points: [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]] }] };
const cases = [
  ['maxlevel_20', file('maxlevel_20.json'), {}],
  ['oscillating_expression', file('oscillating_expression.json'), {}],
  ['hmax_1e-6', file('hmax_1e-6.json'), {}],
  ['radial_1e-6', file('radial_1e-6.json'), {}],
  ['sphere_chord_1e-12', file('sphere_chord_1e-12.json'), {}],
  // A valid, big run (about 1.2M elements) under a large budget: every stage does real work.
  ['hmax_0.001, maxElements 5e6', JSON.stringify({ domain: square, controlSpace: { hmax: 0.001 } }), { maxElements: 5000000 }],
];

const now = () => performance.now();
const cpu = () => { const u = process.cpuUsage(); return (u.user + u.system) / 1000; };
function run(text, options, decide) {
  const times = [];
  const t0 = now(), c0 = cpu();
  let code = 'ok';
  try {
    am.meshCase(text, { ...options, stats: false, onProgress: () => { times.push(now() - t0); return decide(times); } });
  } catch (e) {
    if (!(e instanceof AnisomeshError)) throw e;
    code = e.code;
  }
  return { times, code, wall: now() - t0, cpu: cpu() - c0 };
}
const f = (x) => (x === undefined ? '-' : x.toFixed(1));
const rows = [];
for (const [name, text, options] of cases) {
  for (let r = 0; r < repeat; ++r) {
    const never = run(text, options, () => false);
    const always = run(text, options, () => true);
    let gap = always.times.length ? always.times[0] : undefined;
    for (let i = 1; i < always.times.length; ++i) gap = Math.max(gap, always.times[i] - always.times[i - 1]);
    const half = always.wall / 2;
    const late = run(text, options, (t) => t[t.length - 1] < half);
    const lastCb = late.times[late.times.length - 1];
    rows.push([name, f(never.times[0]), f(never.wall - never.times[0]), never.code, f(always.wall), f(always.cpu),
      always.code, String(always.times.length), f(gap), f(lastCb), f(late.wall - lastCb), late.code]);
  }
}
const head = ['case', 'first cb ms', 'cb->throw ms', 'code', 'true run ms', 'cpu ms', 'code', 'callbacks', 'max gap ms',
  'late cb at ms', 'late cb->throw ms', 'code'];
console.log(`| ${head.join(' | ')} |`);
console.log(`|${head.map(() => '---').join('|')}|`);
for (const row of rows) console.log(`| ${row.join(' | ')} |`);

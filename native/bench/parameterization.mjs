#!/usr/bin/env node
// Section 4.3 benchmark: surface meshing with the parameterization matrix Mp folded into
// the nodes' (u, v) metric, stored in the control nodes (Mt and Mp interpolated alike),
// or computed from the surface at every query, on p2 with holes, the sphere band and the
// two-patch C. Runs the native CLI (options.parameterization set in a copy of each case),
// best of N runs of process CPU time (user + sys, /usr/bin/time), and prints one table with
// the report's 3D quality figures.
// Usage: node native/bench/parameterization.mjs [--runs N] [--cli PATH]
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const args = process.argv.slice(2);
const opt = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);
const cli = opt('--cli', join(root, 'build/native/bin/anisomesh'));
const runs = Number(opt('--runs', 5));
const dir = mkdtempSync(join(tmpdir(), 'anisomesh-mp-'));

const cases = ['surface_p2_holes', 'surface_sphere', 'surface_two_patch_c'];
const modes = ['folded', 'stored', 'computed'];
console.log(`| case | Mp | triangles | CPU s (best of ${runs}) | wall s | queries | Q mean | Q min | edges in [1/√2, √2] | chord dev. / tol |`);
console.log('|---|---|---|---|---|---|---|---|---|---|');
for (const name of cases) {
  const c = JSON.parse(readFileSync(join(root, 'examples/surface', `${name}.json`), 'utf8'));
  for (const mode of modes) {
    c.options = { ...(c.options ?? {}), parameterization: mode };
    const file = join(dir, `${name}_${mode}.json`);
    writeFileSync(file, JSON.stringify(c));
    let best = null;
    for (let k = 0; k < runs; k++) {
      let stderr = '';
      let stdout = '';
      try {
        stdout = execFileSync('/bin/sh', ['-c', `/usr/bin/time -f '@@ %U %S %e' "${cli}" mesh "${file}" -o "${join(dir, 'out.mesh')}" --stats 2>"${join(dir, 'time.txt')}"`], { encoding: 'utf8' });
        stderr = readFileSync(join(dir, 'time.txt'), 'utf8');
      } catch (e) {
        throw new Error(`${name} ${mode}: ${e.message}`);
      }
      const [, u, s, w] = stderr.match(/@@ ([\d.]+) ([\d.]+) ([\d.]+)/);
      const cpu = Number(u) + Number(s);
      if (!best || cpu < best.cpu) best = { cpu, wall: Number(w), stats: JSON.parse(stdout) };
    }
    const st = best.stats;
    const q = st.quality3d ?? {};
    console.log(`| ${name} | ${mode} | ${st.triangles ?? st.elements?.triangles ?? '?'} | ${best.cpu.toFixed(3)} | ${best.wall.toFixed(3)} | ${st.controlSpaceQueries ?? '?'} | ${q.qualityMean?.toFixed(4)} | ${q.qualityMin?.toFixed(4)} | ${q.edgesWithinSqrt2?.toFixed(4)} | ${q.chordDeviationMaxRelative?.toFixed(3)} |`);
  }
}

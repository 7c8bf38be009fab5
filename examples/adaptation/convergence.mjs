#!/usr/bin/env node
// Convergence of the P1 interpolation error under adaptation (issue #13): for four
// functions on the unit square, `anisomesh adapt` from examples/adaptation/square.mesh at
// several target vertex counts N, with uniform, isotropic and anisotropic metrics (L2 norm,
// -hmax 0.2, 5 iterations; uniform: 1), the last mesh's L-inf and L2 errors, and the slope
// of log(error) against log(vertices) (least squares). Prints a Markdown table.
//
// Usage: node examples/adaptation/convergence.mjs [--n 1000,4000,16000] [--pictures DIR]
//   --pictures writes DIR/adapt_<function>_<mode>.svg (isotropic, anisotropic) at the first N,
//   elements coloured by the field.
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh');
const start = join(root, 'examples/adaptation/square.mesh');

export const functions = {
  tanh_layer: 'tanh(40*(y-0.5-0.25*sin(2*pi*x)))',
  circular_front: 'tanh(50*(sqrt((x-0.5)^2+(y-0.5)^2)-0.3))',
  bump_waves: 'exp(-20*((x-0.5)^2+(y-0.5)^2))*(1+0.2*sin(8*pi*x)*sin(8*pi*y))',
  boundary_layer: 'exp(-x/0.01)+x*y',
};

const args = process.argv.slice(2);
const opt = (name, dflt) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : dflt;
};
const ns = opt('--n', '1000,4000,16000').split(',').map(Number);
const pictures = opt('--pictures', null);
const tmp = mkdtempSync(join(tmpdir(), 'anisomesh-adapt-'));

function run(expr, n, mode, svg) {
  const a = ['adapt', start, '-field', expr, '-nv', String(n), '-norm', '2', '-hmax', '0.2', '--stats',
    '-o', join(tmp, 'out.mesh'), '-iterations', mode === 'uniform' ? '1' : '5'];
  if (mode !== 'anisotropic') a.push(`-${mode}`);
  if (svg) a.push('-svg', svg);
  const r = spawnSync(cli, a, { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`${a.join(' ')}: ${r.stderr}`);
  const its = JSON.parse(r.stdout).iterations;
  return its[its.length - 1];
}

function slope(points) {
  const xs = points.map((p) => Math.log(p[0])), ys = points.map((p) => Math.log(p[1]));
  const mx = xs.reduce((s, v) => s + v, 0) / xs.length, my = ys.reduce((s, v) => s + v, 0) / ys.length;
  let sxy = 0, sxx = 0;
  for (let i = 0; i < xs.length; ++i) sxy += (xs[i] - mx) * (ys[i] - my), sxx += (xs[i] - mx) ** 2;
  return sxy / sxx;
}

const fmt = (v) => v.toExponential(2);
console.log('| function | mode | ' + ns.map((n) => `N=${n}: vertices, L-inf, L2`).join(' | ') +
  ' | slope L-inf | slope L2 |');
console.log('|---|---|' + ns.map(() => '---|').join('') + '---|---|');
for (const [name, expr] of Object.entries(functions)) {
  for (const mode of ['uniform', 'isotropic', 'anisotropic']) {
    const rows = ns.map((n, i) => run(expr, n, mode,
      pictures && i === 0 && mode !== 'uniform' ? join(pictures, `adapt_${name}_${mode}.svg`) : null));
    const sInf = slope(rows.map((r) => [r.vertices, r.errorLinf]));
    const s2 = slope(rows.map((r) => [r.vertices, r.errorL2]));
    console.log(`| ${name} | ${mode} | ` +
      rows.map((r) => `${r.vertices}, ${fmt(r.errorLinf)}, ${fmt(r.errorL2)}`).join(' | ') +
      ` | ${sInf.toFixed(2)} | ${s2.toFixed(2)} |`);
  }
}
rmSync(tmp, { recursive: true, force: true });

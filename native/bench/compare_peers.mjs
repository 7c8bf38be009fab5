#!/usr/bin/env node
// Whole-run benchmark: anisomesh's CLI side by side with Debian's BAMG (ffbamg, from
// freefem++) and gmsh (algorithm 7 = BAMG in gmsh) on the same Medit input: a
// background mesh with a metric tensor at its vertices. Every output is measured the
// same way, with the analytic metric the input was sampled from, and one table is printed.
//
// Usage: node native/bench/compare_peers.mjs [--case boundary|shear ...] [--scale S ...]
//                                            [--tools anisomesh,bamg,gmsh] [--keep DIR]
//   scale multiplies the number of elements by about S^2 (S = 1: ~1k triangles; the
//   boundary layer at S = 32 has ~1.1M). Cases: "boundary" (default), a layer along
//   y = 0.5 in the unit square, aspect ratio 100; "shear", a circular shear layer
//   (radius 0.5, across 0.004, along 0.1, thickness 0.06, as examples/shear_layer.json)
//   meshed on the annulus 0.3 < r < 0.7. --large is --scale 32 (the 1M+ case).
import { spawnSync } from 'node:child_process';
import {
  closeSync, existsSync, mkdirSync, mkdtempSync, openSync, readFileSync, rmSync, writeFileSync, writeSync,
} from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh');

// A background mesh: points, triangles (1-based ids), boundary edges [a, b, ref] and the
// boundary loops as point ids (the first one outer, counter-clockwise; holes clockwise).

// --- a boundary layer along y = 0.5 in the unit square, aspect ratio 100 at the layer.
function boundaryLayer(scale) {
  const hx = 0.1 / scale;
  const metric = (x, y) => {
    const hy = Math.min((0.001 + 0.2 * Math.abs(y - 0.5)) / scale, hx);
    return [1 / (hx * hx), 0, 1 / (hy * hy)];
  };
  // Background mesh: x spacing hx/2, y spacing following hy/2 so the layer is resolved.
  const xs = [];
  for (let i = 0, n = Math.ceil(2 / hx); i <= n; i++) xs.push(i / n);
  const ys = [0.5];
  for (let y = 0.5; y < 1; ) {
    y += Math.min((0.001 + 0.2 * (y - 0.5)) / scale, hx) / 2;
    ys.push(Math.min(y, 1));
  }
  const full = [...ys.slice(1).map((y) => 1 - y).reverse(), ...ys];
  return { name: `boundary layer x${scale}`, metric, background: () => gridBackground(xs, full, metric) };
}

function gridBackground(xs, ys, metric) {
  const nx = xs.length, ny = ys.length;
  const id = (i, j) => j * nx + i + 1;
  const pts = [], tris = [], edges = [];
  for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) pts.push([xs[i], ys[j]]);
  for (let j = 0; j + 1 < ny; j++) for (let i = 0; i + 1 < nx; i++)
    tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)], [id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
  for (let i = 0; i + 1 < nx; i++) edges.push([id(i, 0), id(i + 1, 0), 1]);
  for (let j = 0; j + 1 < ny; j++) edges.push([id(nx - 1, j), id(nx - 1, j + 1), 2]);
  for (let i = nx - 1; i > 0; i--) edges.push([id(i, ny - 1), id(i - 1, ny - 1), 3]);
  for (let j = ny - 1; j > 0; j--) edges.push([id(0, j), id(0, j - 1), 4]);
  const loop = [];
  for (let i = 0; i < nx; i++) loop.push(id(i, 0));
  for (let j = 1; j < ny; j++) loop.push(id(nx - 1, j));
  for (let i = nx - 2; i >= 0; i--) loop.push(id(i, ny - 1));
  for (let j = ny - 2; j > 0; j--) loop.push(id(0, j));
  return { pts, tris, edges, loops: [loop], metrics: pts.map(([x, y]) => metric(x, y)) };
}

// --- a circular shear layer (examples/shear_layer.json's field) on an annulus.
function shearLayer(scale) {
  const r0 = 0.5, h0 = 0.004 / scale, ht = 0.1 / scale, thick = 0.06, rIn = 0.3, rOut = 0.7;
  const hn = (r) => { const d = Math.abs(r - r0); return d > thick ? ht : h0 + ((ht - h0) * d) / thick; };
  const metric = (x, y) => {
    const r = Math.hypot(x, y), c = x / r, s = y / r, a = 1 / (hn(r) * hn(r)), b = 1 / (ht * ht);
    // n n^T / hn^2 + t t^T / ht^2 with n = (c, s), t = (-s, c)
    return [a * c * c + b * s * s, (a - b) * c * s, a * s * s + b * c * c];
  };
  const background = () => {
    // Polar grid: radii every hn/2, angles every ht/2 at the outer radius.
    const up = [r0];
    for (let r = r0; r < rOut; ) { r += hn(r) / 2; up.push(Math.min(r, rOut)); }
    const down = [];
    for (let r = r0; r > rIn; ) { r -= hn(r) / 2; down.push(Math.max(r, rIn)); }
    const rs = [...down.reverse(), ...up];
    const na = Math.ceil((2 * Math.PI * rOut) / (ht / 2)), nr = rs.length;
    const id = (i, j) => j * na + (i % na) + 1;
    const pts = [], tris = [], edges = [];
    for (let j = 0; j < nr; j++) for (let i = 0; i < na; i++) {
      const t = (2 * Math.PI * i) / na;
      pts.push([rs[j] * Math.cos(t), rs[j] * Math.sin(t)]);
    }
    for (let j = 0; j + 1 < nr; j++) for (let i = 0; i < na; i++)  // counter-clockwise
      tris.push([id(i, j), id(i + 1, j + 1), id(i + 1, j)], [id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
    const outer = [], inner = [];
    for (let i = 0; i < na; i++) {
      edges.push([id(i, nr - 1), id(i + 1, nr - 1), 1]);
      edges.push([id(na - i, 0), id(na - i - 1, 0), 2]);
      outer.push(id(i, nr - 1));
      inner.push(id(na - i, 0));
    }
    return { pts, tris, edges, loops: [outer, inner], metrics: pts.map(([x, y]) => metric(x, y)) };
  };
  return { name: `shear layer x${scale}`, metric, background };
}

function writeBackground(c, dir) {
  const { pts, tris, edges, loops, metrics } = c.background();
  const v = pts.map(([x, y]) => `${x} ${y} 0`);
  const m = metrics.map((q) => q.join(' '));
  const t = tris.map((k) => `${k.join(' ')} 0`);
  const e = edges.map((k) => k.join(' '));
  const mesh = `MeshVersionFormatted 1\nDimension 2\nVertices\n${v.length}\n${v.join('\n')}\nEdges\n${e.length}\n${e.join('\n')}\nTriangles\n${t.length}\n${t.join('\n')}\nEnd\n`;
  writeFileSync(join(dir, 'bg.mesh'), mesh);
  writeFileSync(join(dir, 'bg.sol'), `MeshVersionFormatted 1\nDimension 2\nSolAtVertices\n${m.length}\n1 3\n${m.join('\n')}\nEnd\n`);
  writeFileSync(join(dir, 'bg.mtr'), `${m.length} 3\n${m.join('\n')}\n`);  // BAMG's metric file
  // gmsh: the same boundary polygons as geometry, the metric as a tensor view on the same triangles.
  // Written in chunks: at the 1M scale the view is larger than a JavaScript string may be.
  const fd = openSync(join(dir, 'bg.pos'), 'w');
  let chunk = ['View "metric" {'];
  for (const tri of tris) {
    const k = tri.map((i) => i - 1);
    const xyz = k.flatMap((i) => [...pts[i], 0]);
    const val = k.flatMap((i) => { const [a, b, d] = metrics[i]; return [a, b, 0, b, d, 0, 0, 0, 1]; });
    chunk.push(`TT(${xyz.join(',')}){${val.join(',')}};`);
    if (chunk.length >= 10000) { writeSync(fd, chunk.join('\n') + '\n'); chunk = []; }
  }
  chunk.push('};');
  writeSync(fd, chunk.join('\n'));
  closeSync(fd);
  const geo = [];
  let p = 0, l = 0;
  const loopIds = [];
  for (const loop of loops) {
    const first = p + 1;
    for (const i of loop) geo.push(`Point(${++p})={${pts[i - 1][0]},${pts[i - 1][1]},0,1};`);
    const lines = [];
    for (let k = 0; k < loop.length; k++) {
      geo.push(`Line(${++l})={${first + k},${first + ((k + 1) % loop.length)}};`);
      lines.push(l);
    }
    geo.push(`Curve Loop(${loopIds.length + 1})={${lines.join(',')}};`);
    loopIds.push(loopIds.length + 1);
  }
  geo.push(`Plane Surface(1)={${loopIds.join(',')}};`, 'Mesh.Algorithm=7;');
  writeFileSync(join(dir, 'bg.geo'), geo.join('\n'));
}

// --- reading outputs and measuring them with the analytic metric
function readMedit(file) {
  const tok = readFileSync(file, 'utf8').split(/\s+/).filter(Boolean);
  const pts = [], tris = [];
  let dimension = 2;
  for (let i = 0; i < tok.length; i++) {
    if (tok[i] === 'Dimension') {
      dimension = Number(tok[++i]);
    } else if (tok[i] === 'Vertices') {
      const n = Number(tok[++i]), stride = dimension + 1;  // coordinates then a reference
      for (let k = 0; k < n; k++) pts.push([Number(tok[i + 1 + k * stride]), Number(tok[i + 2 + k * stride])]);
      i += n * stride;
    } else if (tok[i] === 'Triangles') {
      const n = Number(tok[++i]);
      for (let k = 0; k < n; k++) tris.push([0, 1, 2].map((q) => Number(tok[i + 1 + k * 4 + q]) - 1));
      i += n * 4;
    }
  }
  return { pts, tris };
}

function measure({ pts, tris }, metric) {
  const len = (a, b) => {
    const dx = b[0] - a[0], dy = b[1] - a[1];
    const l = ([m11, m12, m22]) => Math.sqrt(m11 * dx * dx + 2 * m12 * dx * dy + m22 * dy * dy);
    const mid = metric((a[0] + b[0]) / 2, (a[1] + b[1]) / 2);
    return (l(metric(...a)) + 4 * l(mid) + l(metric(...b))) / 6;
  };
  const seen = new Set();
  let inA = 0, inB = 0, edges = 0, qmin = Infinity, qsum = 0, inverted = 0;
  for (const t of tris) {
    const [a, b, c] = t.map((i) => pts[i]);
    for (const [p, q] of [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]]) {
      const key = p < q ? p * 4294967296 + q : q * 4294967296 + p;
      if (seen.has(key)) continue;
      seen.add(key);
      const l = len(pts[p], pts[q]);
      edges++;
      if (l >= Math.SQRT1_2 && l <= Math.SQRT2) inA++;
      if (l >= 0.6 && l <= 1.3) inB++;
    }
    const [m11, m12, m22] = metric((a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3);
    const area = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
    if (area <= 0) inverted++;
    const areaM = Math.abs(area) * Math.sqrt(m11 * m22 - m12 * m12);
    const sq = (u, v) => { const dx = v[0] - u[0], dy = v[1] - u[1]; return m11 * dx * dx + 2 * m12 * dx * dy + m22 * dy * dy; };
    const q = (4 * Math.sqrt(3) * areaM) / (sq(a, b) + sq(b, c) + sq(c, a));
    qmin = Math.min(qmin, q);
    qsum += q;
  }
  return { triangles: tris.length, inA: inA / edges, inB: inB / edges, qmin, qmean: qsum / tris.length, inverted };
}

function run(label, cmd, args, out, dir) {
  if (!existsSync(cmd) && spawnSync('which', [cmd]).status !== 0) return { label, skipped: `${cmd} not found` };
  const t0 = process.hrtime.bigint();
  const r = spawnSync(cmd, args, { cwd: dir, encoding: 'utf8', maxBuffer: 1 << 28 });
  const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
  if (r.status !== 0 || !existsSync(join(dir, out))) return { label, skipped: `failed: ${(r.stderr || r.stdout || '').trim().split('\n').pop()}` };
  return { label, seconds, out: join(dir, out) };
}

const args = process.argv.slice(2);
const scales = [], cases = [];
let keep = null;
let tools = ['anisomesh', 'bamg', 'gmsh'];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--scale') scales.push(Number(args[++i]));
  else if (args[i] === '--large') scales.push(32);
  else if (args[i] === '--case') cases.push(args[++i]);
  else if (args[i] === '--tools') tools = args[++i].split(',');
  else if (args[i] === '--keep') keep = args[++i];
  else { console.error(`unknown argument ${args[i]}`); process.exit(2); }
}
if (scales.length === 0) scales.push(1, 10);
if (cases.length === 0) cases.push('boundary');
const builders = { boundary: boundaryLayer, shear: shearLayer };
for (const k of cases) if (!builders[k]) { console.error(`unknown case ${k} (boundary or shear)`); process.exit(2); }

const rows = [];
for (const kind of cases) for (const scale of scales) {
  const c = builders[kind](scale);
  const dir = keep ? join(keep, `${kind}-${scale}`) : mkdtempSync(join(tmpdir(), 'anisomesh-bench-'));
  mkdirSync(dir, { recursive: true });
  writeBackground(c, dir);
  const runs = [];
  if (tools.includes('anisomesh'))
    runs.push(run('anisomesh', cli, ['remesh', 'bg.mesh', '-sol', 'bg.sol', '-o', 'anisomesh.mesh'], 'anisomesh.mesh', dir));
  if (tools.includes('bamg'))
    runs.push(run('bamg', 'ffbamg', ['-b', 'bg.mesh', '-M', 'bg.mtr', '-o', 'bamg.mesh', '-v', '0', '-nbv', '50000000'], 'bamg.mesh', dir));
  if (tools.includes('gmsh'))
    runs.push(run('gmsh-bamg', 'gmsh', ['-2', 'bg.geo', '-bgm', 'bg.pos', '-o', 'gmsh.mesh', '-v', '1', '-format', 'mesh'], 'gmsh.mesh', dir));
  for (const r of runs) {
    if (r.skipped) { rows.push({ case: c.name, tool: r.label, note: r.skipped }); continue; }
    const q = measure(readMedit(r.out), c.metric);
    rows.push({ case: c.name, tool: r.label, ...q, seconds: r.seconds });
  }
  if (!keep) rmSync(dir, { recursive: true, force: true });
}

const f = (x, d) => (x === undefined ? '' : x.toFixed(d));
const header = ['case', 'tool', 'triangles', 'seconds', 'tri/s', 'l in [.71,1.41]', 'l in [.6,1.3]', 'min Q', 'mean Q', 'inverted'];
const lines = rows.map((r) => r.note
  ? [r.case, r.tool, '', '', '', '', '', '', '', r.note]
  : [r.case, r.tool, String(r.triangles), f(r.seconds, 3), String(Math.round(r.triangles / r.seconds)),
    f(100 * r.inA, 2) + '%', f(100 * r.inB, 2) + '%', f(r.qmin, 3), f(r.qmean, 3), String(r.inverted)]);
const widths = header.map((h, i) => Math.max(h.length, ...lines.map((l) => l[i].length)));
const fmt = (cells) => '| ' + cells.map((s, i) => s.padEnd(widths[i])).join(' | ') + ' |';
console.log(fmt(header));
console.log('|' + widths.map((w) => '-'.repeat(w + 2)).join('|') + '|');
for (const l of lines) console.log(fmt(l));

#!/usr/bin/env node
// Whole-run throughput of `anisomesh remesh` (issue #14), side by side with ffbamg (Debian
// freefem++) on the same Medit files in the same run. Three cases with tensor metrics,
// each on a carrier 2x finer than the requested sizes: a boundary layer (aspect ratio 100),
// a straight shear layer rotated by 30 degrees (the domain is the rotated square) and a
// curved (sinusoidal) front. Prints one table: wall and CPU seconds per stage (from the
// CLI's -v lines), triangles per second, peak RSS, for 1 and 2 threads; and the quality of
// every output against the analytic metric (edges in [1/sqrt2, sqrt2], min and mean Q);
// then the peak RSS at the end of each stage (CLIs whose -v lines give it).
//
// Usage: node native/bench/remesh_throughput.mjs [--size 1e5,1e6,3e6] [--case boundary,rotated,front]
//          [--threads 1,2] [--no-bamg] [--bamg-max 1e6] [--keep DIR [--generate-only]] [--repeat N]
//   --size: target output triangles (the scale of each case is calibrated for it);
//   --bamg-max: largest size ffbamg runs on (it takes ~20x longer).
//   --carrier-factor F: carrier spacing = requested size / F (default 2; ~6.3 puts a 2,000-
//   triangle output on an 80k-triangle carrier).
//   --baseline CLI: also runs another anisomesh build (e.g. the one before a change) on the
//   same files, one thread; a CLI without -v reports the wall seconds of --stats only.
//   --repeat N: every anisomesh build runs N times per case, in turn with the others; a row
//   is the run of median wall time (its CPU and stages), with the range of the N walls.
//   Every row is also printed as JSON on stderr as soon as it is measured. With several sizes
//   the table is followed by the time growth exponents per case and tool (CPU and wall).
import { spawnSync } from 'node:child_process';
import { closeSync, existsSync, mkdirSync, mkdtempSync, openSync, readFileSync, renameSync, rmSync, writeSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = resolve(process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh'));

// ---- cases: metric(x, y) -> [m11, m12, m22]; carrier(): { pts, tris, edges } (1-based)
// A tensor grid mapped by map(s, t) -> [x, y]; boundary edges refs 1..4 (bottom, right, top, left).
function mappedGrid(ss, ts, map) {
  const ns = ss.length, nt = ts.length;
  const id = (i, j) => j * ns + i + 1;
  const pts = new Array(ns * nt);
  for (let j = 0; j < nt; j++) for (let i = 0; i < ns; i++) pts[j * ns + i] = map(ss[i], ts[j]);
  const tris = [];
  for (let j = 0; j + 1 < nt; j++)
    for (let i = 0; i + 1 < ns; i++)
      tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)], [id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
  const edges = [];
  for (let i = 0; i + 1 < ns; i++) edges.push([id(i, 0), id(i + 1, 0), 1]);
  for (let j = 0; j + 1 < nt; j++) edges.push([id(ns - 1, j), id(ns - 1, j + 1), 2]);
  for (let i = ns - 1; i > 0; i--) edges.push([id(i, nt - 1), id(i - 1, nt - 1), 3]);
  for (let j = nt - 1; j > 0; j--) edges.push([id(0, j), id(0, j - 1), 4]);
  return { pts, tris, edges };
}

let carrierFactor = 2;  // carrier spacing = requested size / carrierFactor
const uniform = (h) => {
  const n = Math.ceil(1 / h), out = [];
  for (let i = 0; i <= n; i++) out.push(i / n);
  return out;
};
// Coordinates in [0, 1], symmetric about 0.5, with spacing hn(|t - 0.5|) / carrierFactor.
const graded = (hn) => {
  const half = [0.5];
  for (let t = 0.5; t < 1; ) {
    t += hn(t - 0.5) / carrierFactor;
    half.push(Math.min(t, 1));
  }
  return [...half.slice(1).map((t) => 1 - t).reverse(), ...half];
};
// A metric with size hn across the unit direction n = (nx, ny) and ht along it.
const aligned = (nx, ny, hn, ht) => {
  const a = 1 / (hn * hn), b = 1 / (ht * ht);
  return [a * nx * nx + b * ny * ny, (a - b) * nx * ny, a * ny * ny + b * nx * nx];
};

// A boundary layer along y = 0.5 in the unit square (aspect ratio 100 at the layer).
function boundaryLayer(scale) {
  const ht = 0.1 / scale, hn = (d) => Math.min((0.001 + 0.2 * Math.abs(d)) / scale, ht);
  const metric = (x, y) => aligned(0, 1, hn(y - 0.5), ht);
  return { metric, carrier: () => mappedGrid(uniform(ht / carrierFactor), graded(hn), (s, t) => [s, t]) };
}

// The same layer on the unit square rotated by 30 degrees about its centre.
function rotatedLayer(scale) {
  const ht = 0.1 / scale, hn = (d) => Math.min((0.001 + 0.2 * Math.abs(d)) / scale, ht);
  const c = Math.cos(Math.PI / 6), s = Math.sin(Math.PI / 6);
  const map = (u, v) => [0.5 + c * (u - 0.5) - s * (v - 0.5), 0.5 + s * (u - 0.5) + c * (v - 0.5)];
  const metric = (x, y) => {
    const v = 0.5 - s * (x - 0.5) + c * (y - 0.5);  // the rotated frame's second coordinate
    return aligned(-s, c, hn(v - 0.5), ht);
  };
  return { metric, carrier: () => mappedGrid(uniform(ht / carrierFactor), graded(hn), map) };
}

// A front along y = 0.5 + 0.1 sin(2 pi x): size across from 0.0015 / scale, 0.1 / scale along.
function curvedFront(scale) {
  const ht = 0.1 / scale, hn = (d) => Math.min((0.0015 + 0.2 * Math.abs(d)) / scale, ht);
  const f = (x) => 0.1 * Math.sin(2 * Math.PI * x), df = (x) => 0.2 * Math.PI * Math.cos(2 * Math.PI * x);
  const metric = (x, y) => {
    const g = Math.hypot(df(x), 1);
    return aligned(-df(x) / g, 1 / g, hn((y - 0.5 - f(x)) / g), ht);
  };
  // The carrier follows the front (sheared grid); its t spacing is the smallest across-size
  // over x (the shear shrinks distances by 1 / g at most).
  const gmax = Math.hypot(0.2 * Math.PI, 1);
  const hc = (d) => hn(d) / gmax;
  return { metric, carrier: () => mappedGrid(uniform(ht / carrierFactor), graded(hc), (s, t) => [s, t + f(s)]) };
}

const builders = { boundary: boundaryLayer, rotated: rotatedLayer, front: curvedFront };
// Output triangles at scale 1 ~ K * scale^2 (measured with the current CLI; used to pick scales).
const trianglesAtScale1 = { boundary: 1075, rotated: 1090, front: 1000 };

function writeCarrier(c, dir) {
  const { pts, tris, edges } = c.carrier();
  const fd = openSync(join(dir, 'in.mesh'), 'w');
  const sd = openSync(join(dir, 'in.sol'), 'w');
  const md = openSync(join(dir, 'in.mtr'), 'w');
  const chunked = (fdOut, n, line) => {
    let buf = [];
    for (let i = 0; i < n; i++) {
      buf.push(line(i));
      if (buf.length >= 20000) { writeSync(fdOut, buf.join('\n') + '\n'); buf = []; }
    }
    if (buf.length) writeSync(fdOut, buf.join('\n') + '\n');
  };
  writeSync(fd, `MeshVersionFormatted 1\nDimension 2\nVertices\n${pts.length}\n`);
  chunked(fd, pts.length, (i) => `${pts[i][0]} ${pts[i][1]} 0`);
  writeSync(fd, `Edges\n${edges.length}\n`);
  chunked(fd, edges.length, (i) => edges[i].join(' '));
  writeSync(fd, `Triangles\n${tris.length}\n`);
  chunked(fd, tris.length, (i) => `${tris[i].join(' ')} 0`);
  writeSync(fd, 'End\n');
  const m = (i) => c.metric(pts[i][0], pts[i][1]).join(' ');
  writeSync(sd, `MeshVersionFormatted 1\nDimension 2\nSolAtVertices\n${pts.length}\n1 3\n`);
  chunked(sd, pts.length, m);
  writeSync(sd, 'End\n');
  writeSync(md, `${pts.length} 3\n`);  // BAMG's metric file
  chunked(md, pts.length, m);
  for (const x of [fd, sd, md]) closeSync(x);
  return { vertices: pts.length, triangles: tris.length };
}

// ---- measuring outputs with the analytic metric
function readMedit(file) {
  const text = readFileSync(file, 'latin1');
  let pos = 0;
  const word = () => {
    while (pos < text.length && text.charCodeAt(pos) <= 32) pos++;
    const b = pos;
    while (pos < text.length && text.charCodeAt(pos) > 32) pos++;
    return text.slice(b, pos);
  };
  let dimension = 2, xy = null, tris = null;
  for (let w = word(); w !== '' && w !== 'End'; w = word()) {
    if (w === 'MeshVersionFormatted') word();
    else if (w === 'Dimension') dimension = Number(word());
    else if (w === 'Vertices') {
      const n = Number(word());
      xy = new Float64Array(2 * n);
      for (let k = 0; k < n; k++) {
        xy[2 * k] = Number(word());
        xy[2 * k + 1] = Number(word());
        for (let r = 2; r <= dimension; r++) word();
      }
    } else if (w === 'Triangles') {
      const n = Number(word());
      tris = new Int32Array(3 * n);
      for (let k = 0; k < n; k++) {
        for (let q = 0; q < 3; q++) tris[3 * k + q] = Number(word()) - 1;
        word();
      }
    } else if (w === 'Edges' || w === 'Quadrilaterals' || w === 'Corners' || w === 'RequiredVertices' || w === 'Ridges') {
      const n = Number(word()), per = { Edges: 3, Quadrilaterals: 5 }[w] ?? 1;
      for (let k = 0; k < n * per; k++) word();
    }
  }
  return { xy, tris };
}

function measure({ xy, tris }, metric) {
  const nt = tris.length / 3;
  const len = (p, q) => {
    const ax = xy[2 * p], ay = xy[2 * p + 1], bx = xy[2 * q], by = xy[2 * q + 1], dx = bx - ax, dy = by - ay;
    const l = ([m11, m12, m22]) => Math.sqrt(m11 * dx * dx + 2 * m12 * dx * dy + m22 * dy * dy);
    return (l(metric(ax, ay)) + 4 * l(metric((ax + bx) / 2, (ay + by) / 2)) + l(metric(bx, by))) / 6;
  };
  const seen = new Set();
  let inA = 0, edges = 0, qmin = Infinity, qsum = 0, inverted = 0;
  for (let t = 0; t < nt; t++) {
    const v = [tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]];
    for (let e = 0; e < 3; e++) {
      const p = v[e], q = v[(e + 1) % 3];
      const key = p < q ? p * 4294967296 + q : q * 4294967296 + p;
      if (seen.has(key)) continue;
      seen.add(key);
      const l = len(p, q);
      edges++;
      if (l >= Math.SQRT1_2 && l <= Math.SQRT2) inA++;
    }
    const [a, b, c] = v.map((i) => [xy[2 * i], xy[2 * i + 1]]);
    const [m11, m12, m22] = metric((a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3);
    const area = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
    if (area <= 0) inverted++;
    const areaM = Math.abs(area) * Math.sqrt(m11 * m22 - m12 * m12);
    const sq = (u, w) => { const dx = w[0] - u[0], dy = w[1] - u[1]; return m11 * dx * dx + 2 * m12 * dx * dy + m22 * dy * dy; };
    const q = (4 * Math.sqrt(3) * areaM) / (sq(a, b) + sq(b, c) + sq(c, a));
    qmin = Math.min(qmin, q);
    qsum += q;
  }
  return { triangles: nt, inA: inA / edges, qmin, qmean: qsum / nt, inverted };
}

// Runs cmd under /usr/bin/time: wall, user + sys CPU, peak RSS; stderr kept for -v lines.
function timed(cmd, args, dir) {
  const r = spawnSync('/usr/bin/time', ['-f', 'TIME %e %U %S %M', cmd, ...args],
    { cwd: dir, encoding: 'utf8', maxBuffer: 1 << 28, timeout: Number(process.env.TPUT_TIMEOUT ?? 900) * 1e3 });
  const line = (r.stderr || '').split('\n').find((l) => l.startsWith('TIME '));
  if (r.status !== 0 || !line) {
    const said = (r.stderr || '').trim().split('\n').filter((l) => !l.startsWith('TIME ') && !/^anisomesh: \d+%$/.test(l));
    return { failed: said.slice(-2).join(' ') || `exit ${r.status}` };
  }
  const [wall, user, sys, rssKb] = line.split(' ').slice(1).map(Number);
  const stages = {};
  for (const l of r.stderr.split('\n')) {
    const m = /^anisomesh: stage (.+?)\s+wall ([\d.]+) s cpu ([\d.]+) s(?: rss ([\d.]+) MiB peak ([\d.]+) MiB)?/.exec(l);
    if (m) stages[m[1]] = { wall: Number(m[2]), cpu: Number(m[3]), ...(m[5] ? { rss: Number(m[4]), peak: Number(m[5]) } : {}) };
  }
  // A CLI without -v: the wall seconds of its --stats report (no CPU split).
  const json = (r.stdout || '').trim().split('\n').filter((l) => l.startsWith('{')).pop();
  if (Object.keys(stages).length === 0 && json) {
    const p = JSON.parse(json).pipelineSeconds ?? {};
    const names = { geometry: 'boundary', controlSpace: 'control space', discretization: 'discretization', meshing: 'meshing' };
    for (const [k, v] of Object.entries(names)) if (p[k] !== undefined) stages[v] = { wall: p[k] };
  }
  return { wall, cpu: user + sys, rssMiB: rssKb / 1024, stages, stderr: r.stderr };
}

// ---- main
const argv = process.argv.slice(2);
let generateOnly = false, baseline = null, repeat = 1;
let sizes = [1e5, 1e6], cases = ['boundary', 'rotated', 'front'], threads = [1, 2], bamg = true, bamgMax = 1e6, keep = null;
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  if (a === '--size') sizes = argv[++i].split(',').map(Number);
  else if (a === '--case') cases = argv[++i].split(',');
  else if (a === '--threads') threads = argv[++i].split(',').map(Number);
  else if (a === '--no-bamg') bamg = false;
  else if (a === '--bamg-max') bamgMax = Number(argv[++i]);
  else if (a === '--keep') keep = argv[++i];
  else if (a === '--generate-only') generateOnly = true;
  else if (a === '--baseline') baseline = resolve(argv[++i]);
  else if (a === '--carrier-factor') carrierFactor = Number(argv[++i]);
  else if (a === '--repeat') repeat = Math.max(1, Number(argv[++i]));
  else { console.error(`unknown argument ${a}`); process.exit(2); }
}
for (const k of cases) if (!builders[k]) { console.error(`unknown case ${k}`); process.exit(2); }
const haveBamg = spawnSync('which', ['ffbamg']).status === 0;
// Which options a CLI knows: an unknown one is named in its usage error.
const knows = (bin, ...opt) => !(spawnSync(bin, ['remesh', ...opt], { encoding: 'utf8' }).stderr || '').includes('unknown option');
const cliThreads = knows(cli, '-threads', '1');
const cliVerbose = knows(cli, '-v', '1');
// The 3e6 carriers pass the CLI's default input limit (512 MiB): raised where it can be.
const cliInputLimit = knows(cli, '--max-input-bytes', '1');

const stageNames = ['read', 'boundary', 'control space', 'discretization', 'meshing', 'write', 'report'];
const rows = [];
const pushRow = (row) => {
  rows.push(row);
  const { stderr, ...rest } = row;
  console.error(JSON.stringify(rest));
};
const measured = (row, file, metric) => {
  if (!existsSync(file)) return { ...row, failed: undefined, note: `no output ${file}` };
  return { ...row, ...measure(readMedit(file), metric) };
};
for (const kind of cases)
  for (const size of sizes) {
    const scale = Math.sqrt(size / trianglesAtScale1[kind]);
    const c = builders[kind](scale);
    const dir = keep ? join(keep, `${kind}-${size}-c${carrierFactor}`) : mkdtempSync(join(tmpdir(), 'anisomesh-tput-'));
    mkdirSync(dir, { recursive: true });
    const carrier = writeCarrier(c, dir);
    if (generateOnly) continue;
    const label = `${kind} ${size.toExponential(0)} (carrier ${(carrier.triangles / 1e6).toFixed(2)}M tri)`;
    const tools = threads.map((t) => ({ tool: `anisomesh ${t}t`, bin: cli, t, v: cliVerbose, threads: cliThreads, inputLimit: cliInputLimit }));
    if (baseline) {
      tools.unshift({ tool: 'baseline 1t', bin: baseline, t: 1, v: knows(baseline, '-v', '1'), threads: knows(baseline, '-threads', '1'), inputLimit: knows(baseline, '--max-input-bytes', '1') });
    }
    // --repeat N: the tools run in turn, N rounds (so a busy spell of the host falls on all
    // of them); each row is the run of median wall time, with the range of the N walls.
    const runs = tools.map(() => []);
    const failed = tools.map(() => null);
    for (let round = 0; round < repeat; round++)
      tools.forEach(({ bin, t, v, threads: hasThreads, inputLimit }, k) => {
        if ((t > 1 && !hasThreads) || failed[k]) return;
        const args = ['remesh', 'in.mesh', '-sol', 'in.sol', '-o', `out${k}.mesh`, '--stats'];
        if (v) args.push('-v', '1');
        if (hasThreads) args.push('-threads', String(t));
        if (inputLimit) args.push('--max-input-bytes', '4000000000');
        rmSync(join(dir, `out${k}.mesh`), { force: true });
        const r = timed(bin, args, dir);
        if (r.failed) failed[k] = r.failed;
        else runs[k].push(r);
      });
    tools.forEach(({ tool, t, threads: hasThreads }, k) => {
      if (t > 1 && !hasThreads) { pushRow({ label, tool, note: 'no -threads option' }); return; }
      if (failed[k]) { pushRow({ label, tool, note: failed[k] }); return; }
      const byWall = [...runs[k]].sort((a, b) => a.wall - b.wall);
      const r = byWall[Math.floor((byWall.length - 1) / 2)];
      const range = byWall.length > 1 ? { wallMin: byWall[0].wall, wallMax: byWall[byWall.length - 1].wall } : {};
      pushRow(measured({ label, tool, ...r, ...range, runs: byWall.length }, join(dir, `out${k}.mesh`), c.metric));
      renameSync(join(dir, `out${k}.mesh`), join(dir, 'out.mesh'));
    });
    if (bamg && haveBamg && size <= bamgMax) {
      // -nbv: the vertex budget BAMG allocates up front (a fixed 5e7 costs 4 GB and a minute).
      const nbv = String(Math.round(2 * size + 100000));
      rmSync(join(dir, 'bamg.mesh'), { force: true });
      const r = timed('ffbamg', ['-b', 'in.mesh', '-M', 'in.mtr', '-o', 'bamg.mesh', '-v', '0', '-nbv', nbv], dir);
      if (r.failed) pushRow({ label, tool: 'ffbamg', note: r.failed });
      else pushRow(measured({ label, tool: 'ffbamg', ...r }, join(dir, 'bamg.mesh'), c.metric));
    } else if (bamg) pushRow({ label, tool: 'ffbamg', note: haveBamg ? `skipped (> ${bamgMax})` : 'ffbamg not installed (apt-get install freefem++)' });
    if (!keep) rmSync(dir, { recursive: true, force: true });
  }

const f = (x, d) => (x === undefined || Number.isNaN(x) ? '' : x.toFixed(d));
const stageCell = (r, s) => (r.stages && r.stages[s]
  ? (r.stages[s].cpu === undefined ? f(r.stages[s].wall, 2) : `${f(r.stages[s].wall, 2)}/${f(r.stages[s].cpu, 2)}`) : '');
const wallCell = (r) => (r.wallMin === undefined ? f(r.wall, 2) : `${f(r.wall, 2)} (${f(r.wallMin, 2)}-${f(r.wallMax, 2)})`);
const header = ['case', 'tool', 'triangles', repeat > 1 ? `wall s, median of ${repeat} (range)` : 'wall s', 'CPU s', 'tri/s wall', 'peak RSS MiB', ...stageNames.map((s) => `${s} w/c`),
  'l in [.71,1.41]', 'min Q', 'mean Q', 'inv'];
const lines = rows.map((r) => r.note || r.triangles === undefined
  ? [r.label, r.tool, ...header.slice(2, -1).map(() => ''), r.note ?? '']
  : [r.label, r.tool, String(r.triangles), wallCell(r), f(r.cpu, 2), String(Math.round(r.triangles / r.wall)), f(r.rssMiB, 0),
    ...stageNames.map((s) => stageCell(r, s)), f(100 * r.inA, 2) + '%', f(r.qmin, 3), f(r.qmean, 3), String(r.inverted)]);
const widths = header.map((h, i) => Math.max(h.length, ...lines.map((l) => l[i].length)));
const fmt = (cells) => '| ' + cells.map((s, i) => s.padEnd(widths[i])).join(' | ') + ' |';
console.log(fmt(header));
console.log('|' + widths.map((w) => '-'.repeat(w + 2)).join('|') + '|');
for (const l of lines) console.log(fmt(l));
// Peak RSS so far at the end of each stage (CLIs whose -v lines carry it)
const rssRows = rows.filter((r) => r.stages && Object.values(r.stages).some((x) => x.peak !== undefined));
if (rssRows.length) {
  console.log('');
  const h2 = ['case', 'tool', ...stageNames.map((x) => `${x} peak MiB`)];
  const l2 = rssRows.map((r) => [r.label, r.tool, ...stageNames.map((x) => (r.stages[x]?.peak === undefined ? '' : f(r.stages[x].peak, 0)))]);
  const w2 = h2.map((h, i) => Math.max(h.length, ...l2.map((l) => l[i].length)));
  const fmt2 = (cells) => '| ' + cells.map((c, i) => c.padEnd(w2[i])).join(' | ') + ' |';
  console.log(fmt2(h2));
  console.log('|' + w2.map((w) => '-'.repeat(w + 2)).join('|') + '|');
  for (const l of l2) console.log(fmt2(l));
}
// ffbamg / anisomesh time ratios per case and size
for (const label of [...new Set(rows.map((r) => r.label))]) {
  const b = rows.find((r) => r.label === label && r.tool === 'ffbamg' && !r.note);
  if (!b) continue;
  const parts = rows.filter((r) => r.label === label && r.tool !== 'ffbamg' && !r.note)
    .map((r) => `${r.tool}: ${(b.wall / r.wall).toFixed(1)}x wall`);
  console.log(`${label}: ffbamg ${b.wall.toFixed(2)} s; ${parts.join(', ')}`);
}
// Growth exponents (issue #14: <= 1.02 from 1e5 to 3e6): time ∝ triangles^k, k the
// log-log slope between the smallest and the largest size of a case run by one tool (and
// between consecutive sizes), for CPU and wall seconds; the mesher kernel's share follows
// from the stage columns.
{
  const kindOf = (label) => label.split(' ')[0];
  const ok = rows.filter((r) => !r.note && r.triangles !== undefined);
  const slope = (a, b, key) => Math.log(b[key] / a[key]) / Math.log(b.triangles / a.triangles);
  const lines = [];
  for (const kind of [...new Set(ok.map((r) => kindOf(r.label)))])
    for (const tool of [...new Set(ok.map((r) => r.tool))]) {
      const runs = ok.filter((r) => kindOf(r.label) === kind && r.tool === tool).sort((a, b) => a.triangles - b.triangles);
      if (runs.length < 2) continue;
      const steps = runs.slice(1).map((r, i) => `${runs[i].triangles.toExponential(1)}->${r.triangles.toExponential(1)}: ${slope(runs[i], r, 'cpu').toFixed(3)}`);
      lines.push(`${kind} ${tool}: CPU exponent ${slope(runs[0], runs.at(-1), 'cpu').toFixed(3)}, wall ${slope(runs[0], runs.at(-1), 'wall').toFixed(3)}` +
        ` over ${runs[0].triangles.toExponential(1)}..${runs.at(-1).triangles.toExponential(1)} triangles (CPU by step: ${steps.join('; ')})`);
    }
  if (lines.length) {
    console.log('');
    console.log('time growth exponents (seconds ∝ triangles^k):');
    for (const l of lines) console.log(l);
  }
}

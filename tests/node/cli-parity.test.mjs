// One CLI: the npm CLI (wasm/cli.js) and the native one accept the same commands and
// options and give the same exit code, the same output bytes, the same stdout (JSON
// compared as values) and, for usage errors, the same stderr. Every option of every
// command appears in at least one row of the table below (checked against the usage text).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const nodeCli = join(root, 'wasm/cli.js');
const nativeCli = process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh');
const dir = mkdtempSync(join(tmpdir(), 'anisomesh-parity-'));
test.after(() => rmSync(dir, { recursive: true, force: true }));

const planar = join(root, 'examples/point_source.json');
const surface = join(root, 'examples/surface/surface_p2_holes.json');
const input = join(dir, 'in.mesh'), sol = join(dir, 'in.sol'), inputMsh = join(dir, 'in.msh');
const inputMeshb = join(dir, 'in.meshb'), solb = join(dir, 'in.solb'), cutMeshb = join(dir, 'cut.meshb');

// Each row: the arguments, with OUT standing for the output file (in a folder per CLI).
const rows = [
  [], ['--version'], ['--help'], ['-h'], ['frobnicate'],
  ['metric', '0.5', '0.1', '1'], ['metric', '0', '2', '2'], ['metric', '0.5', '0.1'], ['metric', 'x', '1', '1'],
  ['metric', '0', '0', '1'], ['metric', '1', '1', '1', '1'],
  ['mesh', planar, '-o', 'OUT.mesh', '--stats'], ['mesh', planar, '--output', 'OUT.vtk'], ['mesh', planar, '-o', 'OUT.obj'],
  ['mesh', planar, '-o', 'OUT.svg'], ['mesh', planar, '-o', 'OUT.mesh', '--quads', '--stats'],
  ['mesh', planar, '-o', 'OUT.mesh', '--all-quads'], ['mesh', planar, '-o', 'OUT.mesh', '--no-updates', '--stats'],
  ['mesh', planar, '-o', 'OUT.mesh', '--max-elements', '100000'], ['mesh', planar, '-o', 'OUT.mesh', '--max-elements', '10'],
  ['mesh', planar, '-o', 'OUT.mesh', '--max-elements', '0'], ['mesh', '-in', planar, '-out', 'OUT.mesh', '-v', '1'],
  ['mesh', planar, '-o', 'OUT.mesh', '-v', '0'],
  ['mesh', surface, '-o', 'OUT.svg'], ['mesh', surface, '-o', 'OUT.svg', '--svg-view', '-70,35'],
  ['mesh', surface, '-o', 'OUT.svg', '--svg-uv'], ['mesh', surface, '-o', 'OUT.svg', '--svg-control-space'],
  ['mesh', surface, '-o', 'OUT.svg', '--svg-uv', '--svg-control-space', '--quads'], ['mesh', surface, '-o', 'OUT.mesh', '--stats'],
  ['mesh', surface, '-o', 'OUT.svg', '--svg-view', '10'], ['mesh', surface, '-o', 'OUT.svg', '--svg-view', 'a,b'],
  ['mesh', planar], ['mesh', '-o', 'OUT.mesh'], ['mesh', planar, '-o', 'OUT.stl'], ['mesh', planar, '-o', 'OUT.mesh', '--frob'],
  ['mesh', planar, planar, '-o', 'OUT.mesh'], ['mesh', planar, '-o'], ['mesh', join(dir, 'missing.json'), '-o', 'OUT.mesh'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '--stats'], ['remesh', input, '--sol', sol, '-o', 'OUT.vtk', '-hgrad', '2'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.svg', '--hgrad', '1.5', '-hmin', '0.04', '--hmax', '0.2'],
  ['remesh', '-in', input, '-sol', sol, '-out', 'OUT.mesh', '-hgrad', '-1', '-v', '1'],
  ['remesh', input, '-o', 'OUT.mesh', '-hmax', '0.1', '--stats'], ['remesh', input, '-o', 'OUT.mesh', '--hmin', '0.2'],
  ['remesh', input, '-o', 'OUT.mesh', '-hsiz', '0.08', '--stats'], ['remesh', input, '-o', 'OUT.mesh', '--hsiz', '0.1', '-hgrad', '0'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '--max-elements', '20'],
  ['remesh', input, '-o', 'OUT.mesh'], ['remesh', input, '-sol', sol, '-hsiz', '0.1', '-o', 'OUT.mesh'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '-hgrad', '0.5'], ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '-hmin', '1', '-hmax', '0.1'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '-hsiz', '0'], ['remesh', '-sol', sol, '-o', 'OUT.mesh'],
  ['mesh', planar, '-o', 'OUT.msh'], ['mesh', surface, '-o', 'OUT.msh', '--quads'], ['mesh', planar, '-o', 'OUT.vtu', '--quads'],
  ['mesh', surface, '-o', 'OUT.vtu'], ['remesh', input, '-hmax', '0.1', '-o', 'OUT.vtu'], ['remesh', inputMsh, '-hmax', '0.1', '-o', 'OUT.msh'],
  ['remesh', join(dir, 'in.txt'), '-hmax', '0.1', '-o', 'OUT.mesh'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '--bogus'], ['remesh', input, '-sol', join(dir, 'missing.sol'), '-o', 'OUT.mesh'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '-threads', '2', '--stats'], ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '-threads', 'x'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '-v', '1', '--max-control-nodes', '100000', '--max-input-bytes', '100000000'],
  ['mesh', planar, '-o', 'OUT.mesh', '--max-control-nodes', '10'], ['mesh', planar, '-o', 'OUT.mesh', '--max-input-bytes', '10'],
  ['mesh', surface, '-o', 'OUT.mesh', '-threads', '2', '--stats'], ['mesh', planar, '-o', 'OUT.mesh', '-threads', '0'],
  ['adapt', '--help'], ['adapt', input, '-field', 'sin(4*x)*y', '-o', 'OUT.mesh', '-nv', '300', '-iterations', '2'],
  ['adapt', input, '-field', 'sin(4*x)*y', '-field', 'x*x', '-o', 'OUT.mesh', '-err', '0.01', '-relative', '-norm', '2', '-hmin', '0.01',
    '-hmax', '0.5', '-anisomax', '20', '-hgrad', '2', '-iterations', '1', '-svg', 'OUT.svg', '--control-threshold', '0.5', '--stats'],
  ['adapt', input, '-sol', sol, '-o', 'OUT.vtk', '-nv', '200', '-isotropic', '-norm', 'inf', '--max-elements', '100000'],
  ['adapt', input, '-field', 'x', '-o', 'OUT.mesh', '-nv', '200', '-uniform'], ['adapt', input, '-field', 'x+', '-o', 'OUT.mesh', '-nv', '200'],
  ['adapt', input, '-o', 'OUT.mesh', '-nv', '200'], ['adapt', input, '-field', 'x', '-o', 'OUT.mesh'],
  // Binary Medit and MMG's boundary options.
  ['mesh', planar, '-o', 'OUT.meshb'], ['remesh', inputMeshb, '-sol', solb, '-o', 'OUT.meshb', '--stats'],
  ['remesh', cutMeshb, '-hmax', '0.1', '-o', 'OUT.mesh'],
  ['adapt', inputMeshb, '-field', 'x*y', '-o', 'OUT.meshb', '-nv', '200', '-iterations', '1'],
  ['remesh', input, '-sol', sol, '-o', 'OUT.mesh', '-hausd', '0.0005', '--stats'],
  ['remesh', input, '-hsiz', '0.1', '-hausd', '0.001', '-ar', '30', '-o', 'OUT.vtk'],
  ['remesh', input, '-hsiz', '0.1', '--hausd', '0.001', '-nr', '-o', 'OUT.mesh'], ['remesh', input, '-hsiz', '0.1', '-ar', '10', '-o', 'OUT.mesh'],
  ['remesh', input, '-hsiz', '0.1', '-hausd', '0', '-o', 'OUT.mesh'], ['remesh', input, '-hsiz', '0.1', '-ar', '200', '-o', 'OUT.mesh'],
  ['remesh', input, '-hsiz', '0.1', '-ar', '30', '-nr', '-o', 'OUT.mesh'],
];

function run(cli, args, folder) {
  mkdirSync(folder, { recursive: true });
  const a = args.map((x) => (x.startsWith('OUT') ? join(folder, x) : x));
  const r = cli === 'native' ? spawnSync(nativeCli, a, { encoding: 'utf8' }) : spawnSync(process.execPath, [nodeCli, ...a], { encoding: 'utf8' });
  const files = Object.fromEntries(readdirSync(folder).map((f) => [f, readFileSync(join(folder, f))]));
  const local = (text) => text.split(folder).join('DIR');  // each CLI writes into its own folder
  return { status: r.status, stdout: local(r.stdout), stderr: local(r.stderr), files };
}

// Timings in text lines ("(0.03 s)", "wall 0.000 s cpu 0.000 s", "peak RSS 12.5 MiB") and the
// platform's page size ("transparent huge pages on": glibc natively, never in wasm): masked.
const untimedText = (text) => text.replace(/\d+(\.\d+)?(e-?\d+)? s\b/g, 'T s').replace(/\b(RSS|rss|peak) [\d.]+ MiB/g, '$1 M MiB')
  .replace(/transparent huge pages (on|off)/g, 'transparent huge pages P');
// stdout as a value, without the timings (wall clock, different on every run).
const untimed = (v) => {
  if (Array.isArray(v)) return v.map(untimed);
  if (!v || typeof v !== 'object') return v;
  return Object.fromEntries(Object.entries(v).filter(([k]) => !/seconds|timings/i.test(k)).map(([k, x]) => [k, untimed(x)]));
};
const stdoutValue = (text) => {
  try { return untimed(JSON.parse(text)); } catch { return untimedText(text); }
};

test('npm CLI = native CLI on every command and option', { timeout: 600000 }, () => {
  assert.ok(existsSync(nativeCli), `no native CLI at ${nativeCli}`);
  assert.equal(spawnSync(nativeCli, ['mesh', planar, '-o', input]).status, 0);
  assert.equal(spawnSync(nativeCli, ['mesh', planar, '-o', inputMsh]).status, 0);
  writeFileSync(join(dir, 'in.txt'), 'not a mesh');
  const n = Number(readFileSync(input, 'utf8').match(/Vertices\s+(\d+)/)[1]);
  writeFileSync(sol, `MeshVersionFormatted 1\nDimension 2\nSolAtVertices\n${n}\n1 1\n${'0.06\n'.repeat(n)}End\n`);
  assert.equal(spawnSync(nativeCli, ['mesh', planar, '-o', inputMeshb]).status, 0);
  writeFileSync(cutMeshb, readFileSync(inputMeshb).subarray(0, 100));
  // The .sol as .solb (libMeshb version 2): code, version, Dimension, SolAtVertices, End.
  const b = Buffer.alloc(48 + 8 * n);
  [1, 2, 3, 20, 2, 62, 40 + 8 * n, n, 1, 1].forEach((v, i) => b.writeInt32LE(v, 4 * i));
  for (let i = 0; i < n; i++) b.writeDoubleLE(0.06, 40 + 8 * i);
  b.writeInt32LE(54, 40 + 8 * n);
  writeFileSync(solb, b);

  // Every option in the usage text is exercised by some row.
  const mainHelp = spawnSync(nativeCli, ['--help'], { encoding: 'utf8' }).stdout;
  const help = mainHelp + spawnSync(nativeCli, ['adapt', '--help'], { encoding: 'utf8' }).stdout;
  const options = new Set(help.match(/(?<![\w-])--?[a-z][a-z-]*/g));
  const used = new Set(rows.flat());
  for (const o of options) assert.ok(used.has(o), `option ${o} of the usage text is in no parity row`);
  for (const cmd of mainHelp.matchAll(/^ {2}([a-z]+) /gm)) assert.ok(rows.some((r) => r[0] === cmd[1]), `command ${cmd[1]}`);

  rows.forEach((args, i) => {
    const what = `anisomesh ${args.join(' ')}`;
    const a = run('native', args, join(dir, `native-${i}`));
    const b = run('node', args, join(dir, `node-${i}`));
    assert.equal(b.status, a.status, `${what}: exit ${b.status} vs native ${a.status}\n${b.stderr}\n${a.stderr}`);
    assert.deepEqual(Object.keys(b.files), Object.keys(a.files), `${what}: files written`);
    for (const f of Object.keys(a.files)) assert.ok(a.files[f].equals(b.files[f]), `${what}: ${f} differs`);
    assert.deepEqual(stdoutValue(b.stdout), stdoutValue(a.stdout), `${what}: stdout`);
    if (a.status === 2 || /%\n/.test(a.stderr)) assert.equal(untimedText(b.stderr), untimedText(a.stderr), `${what}: stderr`);
    else if (a.status === 1) assert.equal(b.stderr.match(/^anisomesh: error [A-Z_]+/)?.[0], a.stderr.match(/^anisomesh: error [A-Z_]+/)?.[0], `${what}: ${b.stderr} vs ${a.stderr}`);
  });
});

// Same input, same mesh: the package's remesh(readMesh(text), readSol(text)) writes the bytes
// the native CLI writes for the same files, for a tensor .sol (rotating anisotropic tensors
// whose last bits a metric round trip would move). (A scalar .sol is not compared: readSol
// gives its tensors 1/h^2, whose square root is not h/1 to the last bit, so the package's
// mesh of a scalar .sol can differ from the CLI's in the last bits.)
test('package remesh of the files = native CLI remesh', async () => {
  const { loadAnisomesh } = await import('anisomesh');
  const am = await loadAnisomesh();
  const meshFile = join(dir, 'pkg-in.mesh');
  assert.equal(spawnSync(nativeCli, ['mesh', planar, '-o', meshFile]).status, 0);
  const mesh = am.readMesh(readFileSync(meshFile, 'utf8'));
  const n = mesh.vertices.length / 2;
  const tensorLines = [];
  for (let i = 0; i < n; i++) {
    const x = mesh.vertices[2 * i], y = mesh.vertices[2 * i + 1];
    const a = 0.7 * x + 0.3 * y, h1 = 0.02 + 0.05 * Math.abs(y - 0.5), h2 = 0.08;
    const c = Math.cos(a), s = Math.sin(a), l1 = 1 / (h1 * h1), l2 = 1 / (h2 * h2);
    tensorLines.push(`${l1 * c * c + l2 * s * s} ${(l1 - l2) * c * s} ${l1 * s * s + l2 * c * c}`);
  }
  for (const [type, lines] of [[3, tensorLines]]) {
    const solFile = join(dir, `pkg-${type}.sol`), out = join(dir, `pkg-${type}-out.mesh`);
    const text = `MeshVersionFormatted 1\nDimension 2\nSolAtVertices\n${n}\n1 ${type}\n${lines.join('\n')}\nEnd\n`;
    writeFileSync(solFile, text);
    const r = spawnSync(nativeCli, ['remesh', meshFile, '-sol', solFile, '-o', out], { encoding: 'utf8' });
    assert.equal(r.status, 0, r.stderr);
    const pkg = am.writeMesh(am.remesh(mesh, am.readSol(text, n)).mesh);
    assert.equal(pkg, readFileSync(out, 'utf8'), `type ${type} .sol: the package's mesh differs from the CLI's`);
  }
});

// The package's command line (npx anisomesh) behaves like the native CLI.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const nodeCli = join(root, 'wasm/cli.js');
const nativeCli = process.env.ANISOMESH_CLI ?? join(root, 'build/native/bin/anisomesh');
const dir = mkdtempSync(join(tmpdir(), 'anisomesh-cli-'));
const runNode = (...args) => spawnSync(process.execPath, [nodeCli, ...args], { encoding: 'utf8' });
const runNative = (...args) => spawnSync(nativeCli, args, { encoding: 'utf8' });

test.after(() => rmSync(dir, { recursive: true, force: true }));

test('mesh: same mesh file and --stats as the native CLI', () => {
  assert.ok(existsSync(nativeCli), `no native CLI at ${nativeCli}`);
  const c = join(root, 'examples/fig7_rect_holes_dr2.json');
  const a = runNode('mesh', c, '-o', join(dir, 'node.mesh'), '--stats');
  const b = runNative('mesh', c, '-o', join(dir, 'native.mesh'), '--stats');
  assert.equal(a.status, 0, a.stderr);
  assert.equal(b.status, 0, b.stderr);
  const sa = JSON.parse(a.stdout), sb = JSON.parse(b.stdout);
  for (const k of ['vertices', 'triangles', 'quads', 'edges']) assert.equal(sa[k], sb[k], k);
  assert.equal(sa.quality.mean, sb.quality.mean);
  assert.equal(readFileSync(join(dir, 'node.mesh'), 'utf8'), readFileSync(join(dir, 'native.mesh'), 'utf8'));
});

test('remesh with -sol and -hgrad works like the native CLI', () => {
  const mesh = join(dir, 'in.mesh');
  assert.equal(runNative('mesh', join(root, 'examples/point_source.json'), '-o', mesh).status, 0);
  const n = Number(readFileSync(mesh, 'utf8').match(/Vertices\s+(\d+)/)[1]);
  writeFileSync(join(dir, 'in.sol'), `MeshVersionFormatted 1\nDimension 2\nSolAtVertices\n${n}\n1 1\n${'0.05\n'.repeat(n)}End\n`);
  const a = runNode('remesh', mesh, '-sol', join(dir, 'in.sol'), '-o', join(dir, 'r1.mesh'), '-hgrad', '2', '--stats');
  const b = runNative('remesh', mesh, '-sol', join(dir, 'in.sol'), '-o', join(dir, 'r2.mesh'), '-hgrad', '2', '--stats');
  assert.equal(a.status, 0, a.stderr);
  assert.equal(b.status, 0, b.stderr);
  assert.equal(JSON.parse(a.stdout).triangles, JSON.parse(b.stdout).triangles);
});

test('errors: message on stderr, exit 1 for bad input, 2 for bad usage, no partial output', () => {
  const out = join(dir, 'never.mesh');
  const missing = runNode('mesh', join(dir, 'nope.json'), '-o', out);
  assert.equal(missing.status, 1);
  assert.match(missing.stderr, /error IO_ERROR: cannot open .* for reading/);
  writeFileSync(join(dir, 'bad.json'), '{"domain": {"outer": [{"type": "line", "p1": [0, 0], "p2": [1, 0]}]}}');
  const open = runNode('mesh', join(dir, 'bad.json'), '-o', out);
  assert.equal(open.status, 1);
  assert.match(open.stderr, /error [A-Z_]+: /);
  assert.equal(runNode('frobnicate').status, 2);
  assert.equal(runNode('mesh', join(root, 'examples/point_source.json')).status, 2);
  assert.equal(runNode('mesh', join(root, 'examples/point_source.json'), '-o', join(dir, 'x.stl')).status, 2);
  const budget = runNode('mesh', join(root, 'examples/point_source.json'), '-o', out, '--max-elements', '10');
  assert.equal(budget.status, 1);
  assert.match(budget.stderr, /ELEMENT_BUDGET_EXCEEDED/);
  assert.ok(!existsSync(out), 'no output file after a failed run');
});

// -v 1 stage lines: wasm's clock() is wall time and its page size 64 KiB, so the CLI reads
// the host's /proc; the figures must match what Node itself measures for the process.
test('remesh -v 1: the stage CPU and peak RSS are the process figures', () => {
  const mesh = join(dir, 'v.mesh');
  assert.equal(runNative('mesh', join(root, 'examples/point_source.json'), '-o', mesh).status, 0);
  // The probe writes to a file: the wasm runtime closes the process's fd 2 when it exits.
  const probe = join(dir, 'probe.cjs'), probed = join(dir, 'probe.txt');
  writeFileSync(probe, `process.on('exit', () => { const u = process.resourceUsage();
    require('fs').writeFileSync(${JSON.stringify(probed)}, u.maxRSS + ' ' + (u.userCPUTime + u.systemCPUTime)); });\n`);
  const r = spawnSync(process.execPath, ['-r', probe, nodeCli, 'remesh', mesh, '-o', join(dir, 'v2.mesh'), '-hsiz', '0.01', '-v', '1'],
    { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  const [maxRssKiB, cpuMicros] = readFileSync(probed, 'utf8').split(' ').map(Number);
  const peak = Number(r.stderr.match(/peak RSS ([\d.]+) MiB/)[1]);
  assert.ok(Math.abs(peak - maxRssKiB / 1024) <= 0.2 * (maxRssKiB / 1024), `peak ${peak} MiB, Node ${maxRssKiB} KiB`);
  const cpu = [...r.stderr.matchAll(/ cpu ([\d.]+) s/g)].reduce((s, m) => s + Number(m[1]), 0);
  assert.ok(cpu <= cpuMicros / 1e6 + 0.02, `stages ${cpu} s of CPU, the process ${cpuMicros / 1e6} s`);
});

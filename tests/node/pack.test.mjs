// `npm pack` gives a tarball that installs into an empty folder and imports there.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync, readdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));

test('npm pack tarball installs into an empty folder and imports', { timeout: 120000 }, () => {
  const dir = mkdtempSync(join(tmpdir(), 'anisomesh-pack-'));
  try {
    const out = execFileSync('npm', ['pack', '--pack-destination', dir, '--json'], { cwd: root, encoding: 'utf8' });
    const [info] = JSON.parse(out);
    const files = info.files.map((f) => f.path);
    assert.ok(files.includes('wasm/dist/anisomesh-core.wasm'), `tarball lacks the wasm: ${files}`);
    assert.ok(files.includes('wasm/index.d.ts'));
    for (const f of ['LICENSE', 'README.md', 'wasm/index.cjs', 'wasm/load.js', 'wasm/dist/anisomesh-core.wasm.b64.js', 'wasm/three.d.ts']) {
      assert.ok(files.includes(f), `tarball lacks ${f}`);
    }
    // The README's links to documents (not pictures) resolve inside the package.
    const readme = readFileSync(join(root, 'README.md'), 'utf8');
    for (const [, target] of readme.matchAll(/\]\(([^)#\s]+\.(?:md|d\.ts))\)/g)) {
      assert.ok(files.includes(target), `README links ${target}, which the package does not ship`);
    }
    const pkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8'));
    assert.ok(pkg.keywords.length > 3 && pkg.license === 'MIT');
    assert.match(readFileSync(join(root, 'LICENSE'), 'utf8'), /^MIT License/);
    assert.ok(!files.some((f) => f.startsWith('native/') || f.startsWith('tests/')), 'tarball ships sources or tests');
    const app = join(dir, 'app');
    execFileSync('mkdir', ['-p', app]);
    writeFileSync(join(app, 'package.json'), JSON.stringify({ name: 'app', version: '1.0.0', type: 'module', private: true }));
    execFileSync('npm', ['install', '--no-audit', '--no-fund', '--offline', join(dir, info.filename)], { cwd: app, stdio: 'pipe' });
    assert.ok(readdirSync(join(app, 'node_modules')).includes('anisomesh'));
    writeFileSync(join(app, 'main.mjs'), `
      import { loadAnisomesh, AnisomeshError } from 'anisomesh';
      const am = await loadAnisomesh();
      const c = am.intersectMetrics({ alpha: 0, h1: 0.1, h2: 1 }, { alpha: Math.PI / 2, h1: 0.1, h2: 1 });
      let code = null;
      try { am.metric({ h: -1 }); } catch (e) { code = e instanceof AnisomeshError ? e.code : 'wrong'; }
      console.log(JSON.stringify({ version: am.version, h2: c.h2, code }));
    `);
    const result = JSON.parse(execFileSync('node', ['main.mjs'], { cwd: app, encoding: 'utf8' }));
    assert.equal(result.code, 'INVALID_METRIC');
    assert.ok(Math.abs(result.h2 - 0.1) < 1e-9);
    // The package's command line, as `npx anisomesh` runs it, meshes an example case.
    writeFileSync(join(app, 'case.json'), readFileSync(join(root, 'examples/point_source.json')));
    const stats = JSON.parse(execFileSync(join(app, 'node_modules/.bin/anisomesh'), ['mesh', 'case.json', '-o', 'out.mesh', '--stats'], { cwd: app, encoding: 'utf8' }));
    assert.ok(stats.triangles > 100 && stats.inverted === 0, JSON.stringify(stats).slice(0, 200));
    assert.match(readFileSync(join(app, 'out.mesh'), 'utf8'), /^MeshVersionFormatted/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

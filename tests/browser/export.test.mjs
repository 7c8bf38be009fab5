// Downloads from the app: the .mesh file is read back by the package (readMesh) and by
// the native CLI (remesh under an isotropic .sol written with writeSol).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, readFile, writeFile, access } from 'node:fs/promises';
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadAnisomesh } from '../../wasm/node.js';
import { launch, openPage, settle } from './launch.mjs';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = join(root, 'build/native/bin/anisomesh');

let env, dir;
before(async () => {
  env = await launch();
  dir = await mkdtemp(join(tmpdir(), 'anisomesh-web-'));
});
after(async () => { await env?.close(); });

async function downloadFrom(page, kind) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.locator(`#downloads button[data-dl="${kind}"]`).click()]);
  const path = join(dir, dl.suggestedFilename());
  await dl.saveAs(path);
  return { name: dl.suggestedFilename(), path, text: await readFile(path, 'utf8') };
}

test('the .mesh download is read back by readMesh and by the native CLI', async () => {
  try {
    await access(cli);
  } catch {
    assert.fail(`native CLI not found at ${cli}: build it with\n  cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release && cmake --build build/native -j2 --target anisomesh_cli`);
  }
  const { page, errors } = await openPage(env.browser, env.url, { acceptDownloads: true });
  await settle(page, () => window.anisomeshApp.loadPreset('holes-off'));
  const stats = await page.evaluate(() => window.anisomeshApp.state.lastStats);
  const mesh = await downloadFrom(page, 'mesh');
  assert.equal(mesh.name, 'fig6_rect_holes_nosmooth.mesh');

  const am = await loadAnisomesh();
  const m = am.readMesh(mesh.text, 'mesh');
  const n = m.vertices.length / m.dimension;
  assert.equal(n, stats.vertices);
  assert.equal(m.triangles.length / 3, stats.triangles);

  const metrics = new Float64Array(3 * n);
  for (let i = 0; i < n; i++) metrics.set([1 / 0.3 ** 2, 0, 1 / 0.3 ** 2], 3 * i);  // isotropic h = 0.3
  const sol = join(dir, 'iso.sol');
  await writeFile(sol, am.writeSol(metrics));
  const out = join(dir, 'remeshed.mesh');
  const { stdout } = await promisify(execFile)(cli, ['remesh', mesh.path, '-sol', sol, '-o', out, '--stats']);
  const remeshed = am.readMesh(await readFile(out, 'utf8'), 'mesh');
  assert.ok(remeshed.triangles.length / 3 > 100, stdout);

  // The other downloads are well formed.
  const vtk = await downloadFrom(page, 'vtk');
  assert.match(vtk.text, /^# vtk DataFile/);
  const obj = await downloadFrom(page, 'obj');
  assert.match(obj.text, /^v /m);
  const csVtk = await downloadFrom(page, 'cs-vtk');
  assert.match(csVtk.text, /^# vtk DataFile[\s\S]*TENSORS metric/);
  const csJson = JSON.parse((await downloadFrom(page, 'cs-json')).text);
  assert.ok((csJson.nodes ?? csJson.samples).length > 0);
  const c = JSON.parse((await downloadFrom(page, 'case')).text);
  assert.equal(c.sources.length, 3);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a case JSON file loads through the file input', async () => {
  const { page, errors } = await openPage(env.browser, env.url);
  const c = JSON.parse(await readFile(join(root, 'examples/shear_layer.json'), 'utf8'));
  c.name = 'uploaded';
  const file = join(dir, 'uploaded.json');
  await writeFile(file, JSON.stringify(c));
  await page.locator('#case-file').setInputFiles(file);
  await page.waitForFunction(() => window.anisomeshApp.state.case?.name === 'uploaded' && window.anisomeshApp.idle() && window.anisomeshApp.state.lastError === null);
  assert.equal(await page.locator('#preset').inputValue(), 'custom');
  // A file that is not a case: message, nothing else changes.
  const bad = join(dir, 'bad.json');
  await writeFile(bad, '{"hello": 1}');
  await page.locator('#case-file').setInputFiles(bad);
  await page.locator('#error-io').waitFor({ state: 'visible' });
  assert.match(await page.locator('#error-io').textContent(), /not a case/);
  assert.equal(await page.evaluate(() => window.anisomeshApp.state.case.name), 'uploaded');
  assert.deepEqual(errors, []);
  await page.close();
});

// npm pack refuses to pack without the wasm: wasm/embed.mjs --check (the prepack step after
// the build) fails on a missing or stale embedded copy and passes on the built one.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { cpSync, mkdtempSync, rmSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));

test('prepack check: passes on the build, fails without the wasm or with a stale copy', () => {
  const ok = spawnSync(process.execPath, [join(root, 'wasm/embed.mjs'), '--check'], { encoding: 'utf8' });
  assert.equal(ok.status, 0, ok.stderr);
  const dir = mkdtempSync(join(tmpdir(), 'anisomesh-prepack-'));
  try {
    mkdirSync(join(dir, 'wasm/dist'), { recursive: true });
    cpSync(join(root, 'wasm/embed.mjs'), join(dir, 'wasm/embed.mjs'));
    const missing = spawnSync(process.execPath, [join(dir, 'wasm/embed.mjs'), '--check'], { encoding: 'utf8' });
    assert.equal(missing.status, 1);
    assert.match(missing.stderr, /missing: run `npm run build:wasm`/);
    cpSync(join(root, 'wasm/dist/anisomesh-core.wasm'), join(dir, 'wasm/dist/anisomesh-core.wasm'));
    cpSync(join(root, 'wasm/dist/anisomesh-core.js'), join(dir, 'wasm/dist/anisomesh-core.js'));
    writeFileSync(join(dir, 'wasm/dist/anisomesh-core.wasm.b64.js'), "export const wasmBase64 = 'AGFzbQ==';\n");
    const stale = spawnSync(process.execPath, [join(dir, 'wasm/embed.mjs'), '--check'], { encoding: 'utf8' });
    assert.equal(stale.status, 1);
    assert.match(stale.stderr, /missing or stale/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

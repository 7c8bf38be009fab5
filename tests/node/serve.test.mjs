// web/serve.mjs on a busy port: one readable line and exit 1, no stack trace.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { createServer } from 'node:net';
import { fileURLToPath } from 'node:url';

const serve = fileURLToPath(new URL('../../web/serve.mjs', import.meta.url));

test('busy port: a readable message, exit 1', async () => {
  const blocker = createServer();
  await new Promise((r) => blocker.listen(0, '127.0.0.1', r));
  const { port } = blocker.address();
  try {
    const r = spawnSync(process.execPath, [serve], { env: { ...process.env, PORT: String(port) }, encoding: 'utf8', timeout: 20000 });
    assert.equal(r.status, 1, r.stderr);
    assert.equal(r.stderr, `anisomesh demo: cannot start: port ${port} is already in use (another server running?); try PORT=${port + 1} npm run serve\n`);
  } finally {
    await new Promise((r) => blocker.close(r));
  }
  const bad = spawnSync(process.execPath, [serve], { env: { ...process.env, PORT: 'eighty' }, encoding: 'utf8', timeout: 20000 });
  assert.equal(bad.status, 2);
  assert.match(bad.stderr, /PORT must be an integer/);
});

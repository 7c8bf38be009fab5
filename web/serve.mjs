// Static file server for the demo page: serves the repository root so the page can
// load three.js and lil-gui from node_modules and the package from wasm/.
// Usage: node web/serve.mjs  (PORT from the environment, default 8080)
import { createServer } from 'node:http';
import { readFile, stat } from 'node:fs/promises';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = resolve(fileURLToPath(new URL('..', import.meta.url)));
const types = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.wasm': 'application/wasm',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.mesh': 'text/plain; charset=utf-8',
};

async function handle(req, res) {
  const url = new URL(req.url, 'http://localhost');
  let path = decodeURIComponent(url.pathname);
  if (path === '/' || path === '/web') {
    res.writeHead(302, { Location: '/web/' });
    res.end();
    return;
  }
  if (path.endsWith('/')) path += 'index.html';
  const file = normalize(join(root, path));
  if (file !== root && !file.startsWith(root + sep)) {
    res.writeHead(403).end('forbidden');
    return;
  }
  try {
    const info = await stat(file);
    if (!info.isFile()) throw new Error('not a file');
    const body = await readFile(file);
    // Cross-origin isolation (COOP + COEP): SharedArrayBuffer, which lets the page cancel a
    // stale mesh job inside its worker instead of replacing the worker (web/jobs.js). Every
    // resource is served from here, so require-corp blocks nothing; ?isolation=off on the
    // page leaves it out (the page then cancels by terminating workers, as on hosts
    // without these headers).
    const isolate = url.searchParams.get('isolation') !== 'off';
    res.writeHead(200, {
      'Content-Type': types[extname(file)] ?? 'application/octet-stream',
      'Cache-Control': 'no-cache',
      ...(isolate ? { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' } : {}),
    });
    res.end(body);
  } catch {
    res.writeHead(404, { 'Content-Type': 'text/plain' }).end(`not found: ${path}`);
  }
}

/** Starts the server; resolves to { server, url } once it listens (port 0 = any free port). */
export function startServer({ port = 8080, host = '127.0.0.1' } = {}) {
  return new Promise((resolvePromise, reject) => {
    const server = createServer((req, res) => {
      handle(req, res).catch(() => res.writeHead(500).end());
    });
    server.once('error', reject);
    server.listen(port, host, () => {
      const { port: actual } = server.address();
      resolvePromise({ server, url: `http://localhost:${actual}/web/` });
    });
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const port = Number(process.env.PORT ?? 8080);
  if (!Number.isInteger(port) || port < 0 || port > 65535) {
    console.error(`anisomesh demo: PORT must be an integer in [0, 65535], got '${process.env.PORT}'`);
    process.exit(2);
  }
  try {
    const { url } = await startServer({ port });
    console.log(`anisomesh demo: ${url}`);
  } catch (e) {
    // One readable line instead of a stack trace.
    const why = e.code === 'EADDRINUSE' ? `port ${port} is already in use (another server running?); try PORT=${port + 1} npm run serve`
      : e.code === 'EACCES' ? `no permission to listen on port ${port}; try a port above 1023 (PORT=8080)`
      : e.message;
    console.error(`anisomesh demo: cannot start: ${why}`);
    process.exit(1);
  }
}

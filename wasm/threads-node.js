// Node entry of the multithreaded core ('anisomesh/threads'): the module built with Emscripten
// pthreads, its pool as worker_threads (one per core beside the caller, 2 to 7:
// wasm/threads_pre.js). setThreads(n) on the loaded API uses them; the default is 1 thread.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import createAnisomeshCore from './dist/anisomesh-core-mt.js';
import { makeThreadedLoader } from './load.js';

export { AnisomeshError } from './api.js';

const dist = new URL('./dist/', import.meta.url);
// Emscripten 3.1.6's glue for Node is CommonJS at heart: in an ES module it finds require and
// __dirname as globals only (they are set while it loads). Its worker script is CommonJS too,
// copied to .worker.cjs (this package is "type": "module").
function withCommonJsGlobals(create) {
  return (glue) => {
    const saved = { require: globalThis.require, __dirname: globalThis.__dirname };
    globalThis.require = createRequire(import.meta.url);
    globalThis.__dirname = fileURLToPath(dist);
    const restore = () => Object.assign(globalThis, saved);
    try {
      const ready = create(glue);
      return Promise.resolve(ready).then((core) => {
        restore();
        core.unrefWorkers();
        return core;
      }, (e) => {
        restore();
        throw e;
      });
    } catch (e) {
      restore();
      throw e;
    }
  };
}

const workerPath = fileURLToPath(new URL('./anisomesh-core-mt.worker.cjs', dist));
/**
 * Loads the multithreaded core (cached per source and threads; a failed load is retried).
 * threads: the most threads it will run, 2 to 8 (its pool: threads - 1 workers); default one per core.
 */
export const loadAnisomesh = makeThreadedLoader(() => readFile(new URL('./anisomesh-core-mt.wasm', dist)),
  withCommonJsGlobals(createAnisomeshCore), {
    locateFile: (path) => (path.endsWith('.worker.js') ? workerPath : path),
    mainScriptUrlOrBlob: new URL('./anisomesh-core-mt.js', dist).href,
  });

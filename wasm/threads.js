// Browser / Web Worker entry of the multithreaded core ('anisomesh/threads'): the same API as
// 'anisomesh', over the module built with Emscripten pthreads (a pool of Web Workers on one
// SharedArrayBuffer, one per core beside the caller: 2 to 7, wasm/threads_pre.js). Needs a
// cross-origin isolated page (COOP + COEP headers); call setThreads(n) on the loaded API to
// use the pool (it returns the count in effect), the default is 1 thread.
// Blocking joins are only allowed off the page's main thread: use it in a Web Worker.
import createAnisomeshCore from './dist/anisomesh-core-mt.js';
import { AnisomeshError } from './api.js';
import { fetchWasm, makeThreadedLoader } from './load.js';

export { AnisomeshError } from './api.js';

const workerUrl = new URL('./dist/anisomesh-core-mt.worker.js', import.meta.url).href;
const load = makeThreadedLoader(() => fetchWasm(new URL('./dist/anisomesh-core-mt.wasm', import.meta.url).href), createAnisomeshCore, {
  locateFile: (path) => (path.endsWith('.worker.js') ? workerUrl : path),
  mainScriptUrlOrBlob: new URL('./dist/anisomesh-core-mt.js', import.meta.url).href,
});

/**
 * Loads the multithreaded core (options as 'anisomesh': wasmUrl, wasmBinary of
 * anisomesh-core-mt.wasm; threads: the most threads it will run, 2 to 8, which sizes its
 * worker pool, default one per core). Rejects with WASM_LOAD_FAILED where SharedArrayBuffer is missing
 * (a page that is not cross-origin isolated).
 */
export function loadAnisomesh(options = {}) {
  if (typeof SharedArrayBuffer === 'undefined' || globalThis.crossOriginIsolated === false) {
    return Promise.reject(new AnisomeshError('WASM_LOAD_FAILED',
      "anisomesh/threads needs SharedArrayBuffer: serve the page cross-origin isolated (COOP: same-origin, COEP: require-corp), or use 'anisomesh'"));
  }
  return load(options);
}

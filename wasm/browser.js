// Browser / bundler / Web Worker entry point: fetches the wasm next to this file.
import createAnisomeshCore from './dist/anisomesh-core.js';
import { wrapCore } from './api.js';

export { AnisomeshError } from './api.js';

let instance = null;

/** Loads the WebAssembly core once and returns the API object (cached). */
export function loadAnisomesh() {
  if (!instance) {
    // new URL(..., import.meta.url) is the pattern bundlers recognise as an asset.
    const wasmUrl = new URL('./dist/anisomesh-core.wasm', import.meta.url).href;
    instance = createAnisomeshCore({ locateFile: () => wasmUrl }).then(wrapCore);
  }
  return instance;
}

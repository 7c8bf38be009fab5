// Node entry point: reads the wasm binary from the package folder.
import { readFile } from 'node:fs/promises';
import createAnisomeshCore from './dist/anisomesh-core.js';
import { wrapCore } from './api.js';

export { AnisomeshError } from './api.js';

let instance = null;

/** Loads the WebAssembly core once and returns the API object (cached). */
export function loadAnisomesh() {
  if (!instance) {
    instance = (async () => {
      const wasmBinary = await readFile(new URL('./dist/anisomesh-core.wasm', import.meta.url));
      return wrapCore(await createAnisomeshCore({ wasmBinary }));
    })();
  }
  return instance;
}

// Browser / bundler / Web Worker entry point. The packaged wasm is found with the
// new URL('./dist/anisomesh-core.wasm', import.meta.url) pattern (Vite, webpack, Parcel and
// a plain static folder resolve it); where a bundler leaves that URL dangling (esbuild),
// the wasm embedded in dist/anisomesh-core.wasm.b64.js is used instead.
import createAnisomeshCore from './dist/anisomesh-core.js';
import { fetchWasm, makeLoader } from './load.js';

export { AnisomeshError } from './api.js';

async function packagedWasm() {
  let first;
  try {
    return await fetchWasm(new URL('./dist/anisomesh-core.wasm', import.meta.url).href);
  } catch (e) {
    first = e;
  }
  try {
    const { wasmBase64 } = await import('./dist/anisomesh-core.wasm.b64.js');
    const text = atob(wasmBase64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return bytes;
  } catch (e) {
    throw first;
  }
}

/**
 * Loads the WebAssembly core and returns the API object. options.wasmUrl (where the .wasm is
 * served) or options.wasmBinary (its bytes) override the packaged file. Cached per source;
 * a failed load throws AnisomeshError 'WASM_LOAD_FAILED' and the next call tries again.
 */
export const loadAnisomesh = makeLoader(packagedWasm, createAnisomeshCore);

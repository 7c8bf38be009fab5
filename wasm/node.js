// Node entry point: reads the wasm binary from the package folder (or options.wasmUrl /
// options.wasmBinary, as in the browser).
import { readFile } from 'node:fs/promises';
import createAnisomeshCore from './dist/anisomesh-core.js';
import { makeLoader } from './load.js';

export { AnisomeshError } from './api.js';

/** Loads the WebAssembly core and returns the API object (cached; a failed load is retried). */
export const loadAnisomesh = makeLoader(() => readFile(new URL('./dist/anisomesh-core.wasm', import.meta.url)), createAnisomeshCore);

// Loading the WebAssembly core, shared by the Node and browser entry points: the wasm bytes
// come from options.wasmBinary, options.wasmUrl or the entry point's default source; the
// module is instantiated here (emscripten's instantiateWasm hook), so every failure becomes
// an AnisomeshError 'WASM_LOAD_FAILED' and a failed load is forgotten (a later call retries).
import { AnisomeshError, wrapCore } from './api.js';

function loadError(message, cause) {
  const e = new AnisomeshError('WASM_LOAD_FAILED', message);
  if (cause !== undefined) e.cause = cause;
  return e;
}

function describe(e) {
  return e?.message ?? String(e);
}

// Instantiates the core (the glue's factory create, with the extra module options glue)
// from a function that returns the wasm bytes (or a compiled module).
function instantiate(getBytes, where, create, glue) {
  return new Promise((resolve, reject) => {
    const fail = (e) => reject(e instanceof AnisomeshError ? e : loadError(`cannot load the anisomesh core from ${where}: ${describe(e)}`, e));
    let core;
    try {
      core = create({
        instantiateWasm(imports, done) {
          Promise.resolve()
            .then(getBytes)
            .then((bytes) => WebAssembly.instantiate(bytes, imports).then((r) => (r.instance ? r : { instance: r, module: bytes })))
            // The module too: the threaded module's workers instantiate it again.
            .then((r) => done(r.instance, r.module), fail);
          return {};
        },
        // The bytes come from getBytes: the glue must not build its own URL (in an IIFE
        // bundle import.meta.url is undefined and new URL() would throw).
        locateFile: (path) => path,
        onAbort: (what) => fail(new Error(String(what))),
        print: () => {},
        printErr: () => {},
        ...glue,
      });
    } catch (e) {
      fail(e);
      return;
    }
    Promise.resolve(core).then((c) => resolve(wrapCore(c)), fail);
  });
}

function checkBinary(bytes, where) {
  const view = bytes instanceof ArrayBuffer ? new Uint8Array(bytes) : bytes;
  if (!(view instanceof Uint8Array)) throw loadError(`${where}: expected an ArrayBuffer or Uint8Array of the .wasm file`);
  if (view.length < 8 || view[0] !== 0 || view[1] !== 0x61 || view[2] !== 0x73 || view[3] !== 0x6d) {
    throw loadError(`${where}: not a WebAssembly binary (${view.length} bytes, no '\\0asm' header)`);
  }
  return view;
}

/** Fetches a .wasm URL and returns its bytes (an AnisomeshError on a network error or a non-2xx answer). */
export async function fetchWasm(url) {
  let response;
  try {
    response = await fetch(url);
  } catch (e) {
    throw loadError(`cannot fetch the anisomesh core at ${url}: ${describe(e)}`, e);
  }
  if (!response.ok) throw loadError(`cannot fetch the anisomesh core at ${url}: HTTP ${response.status}`);
  return checkBinary(new Uint8Array(await response.arrayBuffer()), String(url));
}

/**
 * Makes the threaded entry points' loadAnisomesh({ wasmUrl, wasmBinary, threads }): threads
 * (2 to 8) sizes the instance's worker pool (threads - 1 workers, each a Web Worker or
 * worker_thread holding the module), else one worker per core (wasm/threads_pre.js). One
 * cached instance per pool size and source.
 */
export function makeThreadedLoader(defaultBytes, create, glue = {}) {
  const loaders = new Map();
  return function loadAnisomesh(options = {}) {
    const threads = options !== null && typeof options === 'object' ? options.threads : undefined;
    if (threads !== undefined && !(Number.isInteger(threads) && threads >= 2 && threads <= 8)) {
      return Promise.reject(new AnisomeshError('INVALID_ARGUMENT', `loadAnisomesh: threads must be an integer from 2 to 8, got ${String(threads)}`));
    }
    const key = threads ?? 0;
    if (!loaders.has(key)) loaders.set(key, makeLoader(defaultBytes, create, threads ? { ...glue, anisomeshPoolSize: threads - 1 } : glue));
    return loaders.get(key)(options);
  };
}

/**
 * Makes loadAnisomesh({ wasmUrl, wasmBinary }) for an entry point whose defaultBytes() gives
 * the packaged wasm, create is the Emscripten glue's factory and glue extra module options
 * (the threaded module's worker script). Successful loads are cached per source; failed ones are not.
 */
export function makeLoader(defaultBytes, create, glue = {}) {
  const byUrl = new Map();
  const byBinary = new WeakMap();
  return function loadAnisomesh(options = {}) {
    if (options === null || typeof options !== 'object') {
      return Promise.reject(new AnisomeshError('INVALID_ARGUMENT', 'loadAnisomesh: options must be an object { wasmUrl?, wasmBinary? }'));
    }
    const { wasmUrl, wasmBinary } = options;
    if (wasmUrl !== undefined && wasmBinary !== undefined) {
      return Promise.reject(new AnisomeshError('INVALID_ARGUMENT', 'loadAnisomesh: give wasmUrl or wasmBinary, not both'));
    }
    if (wasmUrl !== undefined && typeof wasmUrl !== 'string' && !(wasmUrl instanceof URL)) {
      return Promise.reject(new AnisomeshError('INVALID_ARGUMENT', 'loadAnisomesh: wasmUrl must be a string or URL'));
    }
    let cache, key, getBytes, where;
    if (wasmBinary !== undefined) {
      if (wasmBinary === null || typeof wasmBinary !== 'object') {
        return Promise.reject(new AnisomeshError('INVALID_ARGUMENT', 'loadAnisomesh: wasmBinary must be an ArrayBuffer or Uint8Array'));
      }
      [cache, key, where] = [byBinary, wasmBinary, 'options.wasmBinary'];
      getBytes = () => checkBinary(wasmBinary, 'options.wasmBinary');
    } else if (wasmUrl !== undefined) {
      [cache, key, where] = [byUrl, String(wasmUrl), String(wasmUrl)];
      getBytes = () => fetchWasm(String(wasmUrl));
    } else {
      [cache, key, where] = [byUrl, '', 'the package'];
      getBytes = defaultBytes;
    }
    let pending = cache.get(key);
    if (!pending) {
      pending = instantiate(getBytes, where, create, glue);
      cache.set(key, pending);
      pending.catch(() => cache.delete(key));
    }
    return pending;
  };
}

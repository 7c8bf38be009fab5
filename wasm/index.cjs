// CommonJS entry point (`require('anisomesh')`, Node >= 18): the same API as the ES module,
// loaded by a dynamic import() inside loadAnisomesh(), which is asynchronous anyway.
'use strict';

const errorKey = Symbol.for('anisomesh.AnisomeshError');

/** Error thrown by every anisomesh call that fails; the same class as the ES module's. */
const AnisomeshError = (globalThis[errorKey] ??= class AnisomeshError extends Error {
  constructor(code, message) {
    super(message);
    this.name = 'AnisomeshError';
    this.code = code;
  }
});

/** Loads the WebAssembly core (see wasm/node.js): a Promise of the API object. */
function loadAnisomesh(options) {
  return import('./node.js').then((m) => m.loadAnisomesh(options));
}

module.exports = { AnisomeshError, loadAnisomesh };

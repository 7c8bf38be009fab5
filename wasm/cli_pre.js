/* global Module */  // the Emscripten loader this is linked into defines it
// Linked before the npm CLI's loader (--pre-js): Node's fetch refuses file paths, so the
// loader is handed the wasm bytes, read beside it; a missing file is a coded error.
try {
  Module['wasmBinary'] = require('fs').readFileSync(require('path').join(__dirname, 'anisomesh-cli.wasm'));
} catch (e) {
  process.stderr.write('anisomesh: error WASM_LOAD_FAILED: ' + (e.message || e) + ' (build it: npm run build:wasm)\n');
  process.exit(1);
}

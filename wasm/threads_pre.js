/* global Module */  // defined by the Emscripten glue this is linked into
// Prepended to the threaded module's glue (--pre-js): the size of its pthread pool, which
// PTHREAD_POOL_SIZE (wasm/CMakeLists.txt) reads when the module starts. One worker per core
// beside the caller's thread (navigator.hardwareConcurrency in browsers and workers, the
// available parallelism in Node), 2 at least (so setThreads(3) works on any machine), 7 at
// most. setThreads() clamps to the pool and the caller (wasm/bindings.cpp).
if (!(Module['anisomeshPoolSize'] > 0)) {
  let cores = 2;
  if (typeof navigator === 'object' && navigator.hardwareConcurrency > 0) {
    cores = navigator.hardwareConcurrency;
  } else if (typeof process === 'object' && process.versions && process.versions.node && typeof require === 'function') {
    const os = require('os');
    cores = typeof os.availableParallelism === 'function' ? os.availableParallelism() : os.cpus().length;
  }
  Module['anisomeshPoolSize'] = Math.max(2, Math.min(7, cores - 1));
}

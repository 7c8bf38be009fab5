/* global Module, ENVIRONMENT_IS_NODE, PThread */  // defined by the Emscripten glue this is linked into
// Appended to the threaded module's glue (--post-js): lets the Node entry unref the worker
// pool once the module is ready, so that a script ends when its own work does (Emscripten
// 3.1.6 keeps a process alive as long as its workers exist).
Module['unrefWorkers'] = function () {
  if (!ENVIRONMENT_IS_NODE) return;
  for (const w of PThread.unusedWorkers.concat(PThread.runningWorkers)) w.unref();
};

#!/usr/bin/env bash
# Builds the WebAssembly module into wasm/dist/ (incremental: a second run only
# relinks what changed). Needs Debian's emscripten (see .ci/setup.sh).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build/wasm"
export NODE_PATH=/usr/share/nodejs   # emcc 3.1.6 finds acorn there
if [ ! -f "$build/CMakeCache.txt" ]; then
  emcmake cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CROSSCOMPILING_EMULATOR=/usr/bin/node \
    -DEigen3_DIR=/usr/share/eigen3/cmake \
    -DANISOMESH_BUILD_TESTS=OFF -DANISOMESH_BUILD_BENCHMARKS=OFF \
    -DCMAKE_UNITY_BUILD=ON >/dev/null  # see tests/run-all.sh
fi
cmake --build "$build" -j"$(nproc)"
node "$root/wasm/embed.mjs"   # the base64 copy the browser entry falls back to
ls -l "$root/wasm/dist/"anisomesh-core.* | awk '{print "built " $9 " (" $5 " bytes)"}'

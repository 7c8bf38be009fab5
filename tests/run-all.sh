#!/usr/bin/env bash
# Every test of anisomesh, in order: native (ctest), lint (clang-format, clang-tidy, eslint),
# native under AddressSanitizer +
# UndefinedBehaviorSanitizer, node (the npm package), browser (headless Chromium).
# Builds what is needed, incrementally, into build/.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
jobs="$(nproc)"
start=$SECONDS
stage() { echo; echo "=== $1 ($((SECONDS - start)) s)"; }
logs="$root/build/test-logs"
mkdir -p "$logs"
rm -f "$logs"/*.log
# Runs a test layer, keeping its output to count passes and failures at the end.
run_layer() { local name="$1"; shift; "$@" 2>&1 | tee "$logs/$name.log"; }

# Unity builds (CMake batches of 8 sources per compiler run) for native, sanitize and wasm:
# Eigen, gtest, nlohmann::json and their inline code are parsed and compiled once per batch
# instead of once per file. Cold builds on the 2-core machine, CPU seconds: Release 911 -> 375,
# ASan + UBSan 1367 -> 696. Names private to a source file must be unique across the target.
stage "native: build and ctest"
cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release -DANISOMESH_WERROR=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build build/native -j"$jobs"
run_layer native bash -c 'cd build/native && ctest --output-on-failure -j"$0"' "$jobs"

stage "lint: clang-format, clang-tidy, eslint"
run_layer lint bash tests/lint.sh

stage "native under ASan + UBSan: build and ctest"
# Batches of 16 here: a cold build took 602 CPU s (344 s wall) against 696 with batches of 8.
cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" -DANISOMESH_SANITIZE=ON \
  -DANISOMESH_BUILD_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 >/dev/null
cmake --build build/sanitize -j"$jobs"
run_layer sanitize bash -c 'cd build/sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j"$0"' "$jobs"

# libFuzzer targets (tests/fuzz), when clang is installed: the kept regressions, then a
# short run of each target (10 s each; tests/fuzz/run.sh SECONDS for longer).
# Opt-in (ANISOMESH_FUZZ=1): on the 2-core machine the stage took 327 s (fresh build dir, warm
# ccache: build 279 s, regressions + 4 x 10 s 48 s; a cold build 11 min), over its 4-minute share.
if [ "${ANISOMESH_FUZZ:-0}" = 1 ] && command -v clang++ >/dev/null 2>&1; then
  stage "fuzz: libFuzzer targets (clang, ASan + UBSan), regressions and 10 s per target"
  CC=clang CXX=clang++ cmake -S . -B build/fuzz -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 -DANISOMESH_BUILD_FUZZ=ON \
    -DANISOMESH_BUILD_TESTS=OFF -DANISOMESH_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build build/fuzz -j"$jobs"
  run_layer fuzz bash tests/fuzz/run.sh 10 || true
fi

stage "wasm: build"
bash wasm/build.sh

# The node test files one per core: node --test runs one file at a time on the 2-core machine
# (its default is one less than the cores) and each file is a single-threaded node process.
stage "node: node --test tests/node"
run_layer node node --test --test-concurrency="$jobs" tests/node/

stage "browser: node --test tests/browser (headless Chromium)"
run_layer browser node --test --test-concurrency=1 tests/browser/

# One closing line for all layers: ctest "... N tests failed out of M", node "# pass N".
passed=0; failed=0
for layer in native sanitize; do
  line=$(grep -E 'tests passed, [0-9]+ tests? failed out of [0-9]+' "$logs/$layer.log" | tail -1)
  total=$(sed -E 's/.*out of ([0-9]+).*/\1/' <<<"$line"); bad=$(sed -E 's/.* ([0-9]+) tests? failed.*/\1/' <<<"$line")
  echo "$layer (ctest): $((total - bad)) passed, $bad failed"
  passed=$((passed + total - bad)); failed=$((failed + bad))
done
if [ -f "$logs/fuzz.log" ]; then
  p=$(grep -c '^fuzz .*: passed' "$logs/fuzz.log" || true); f=$(grep -c '^fuzz .*: failed' "$logs/fuzz.log" || true)
  echo "fuzz (libFuzzer): $p passed, $f failed"
  passed=$((passed + p)); failed=$((failed + f))
fi
for layer in lint node browser; do
  p=$(grep -E '^# pass [0-9]+' "$logs/$layer.log" | tail -1 | awk '{print $3}')
  f=$(grep -E '^# fail [0-9]+' "$logs/$layer.log" | tail -1 | awk '{print $3}')
  echo "$layer (node --test): $p passed, $f failed"
  passed=$((passed + p)); failed=$((failed + f))
done
echo "all test layers ran in $((SECONDS - start)) s"
echo "$passed passed, $failed failed"

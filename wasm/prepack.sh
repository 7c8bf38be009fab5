#!/usr/bin/env bash
# npm pack / npm publish: builds the wasm when Emscripten is installed, then refuses to pack
# unless wasm/dist holds the module, its glue and the embedded copy, all matching.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if command -v emcc >/dev/null; then bash "$root/wasm/build.sh" >&2; fi
node "$root/wasm/embed.mjs" --check >&2

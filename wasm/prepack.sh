#!/usr/bin/env bash
# npm pack / npm publish: builds the wasm when Emscripten is installed, then refuses to pack
# unless wasm/dist holds the module, its glue and the embedded copy, all matching.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if command -v emcc >/dev/null; then bash "$root/wasm/build.sh" >&2; fi
node "$root/wasm/embed.mjs" --check >&2
# The npm CLI: the native CLI compiled for Node (wasm/CMakeLists.txt, anisomesh_wasm_cli).
for f in anisomesh-cli.cjs anisomesh-cli.wasm; do
  [ -s "$root/wasm/dist/$f" ] || { echo "prepack: wasm/dist/$f is missing (npm run build:wasm)" >&2; exit 1; }
done

#!/usr/bin/env node
// The package's command line (`npx anisomesh ...`): the native CLI itself (native/cli/*.cpp)
// compiled to WebAssembly with direct file access (wasm/CMakeLists.txt, anisomesh_wasm_cli),
// so its commands, options, usage text, messages, exit codes and output bytes are the native
// ones by construction (tests/node/cli-parity.test.mjs runs both on every option). The
// loader takes its arguments from process.argv and sets the exit code.
import { createRequire } from 'node:module';

createRequire(import.meta.url)('./dist/anisomesh-cli.cjs');

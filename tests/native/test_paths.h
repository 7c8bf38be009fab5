#pragma once
// Where the tests find the source tree and the CLI. The paths are compiled into one
// object (test_paths.cpp) so that the other test objects do not depend on where the
// checkout lives (ccache reuses them across checkouts).
namespace anisomesh_test {
const char* sourceDir();  // the repository's root
const char* cliPath();    // the built anisomesh CLI
}  // namespace anisomesh_test

#define ANISOMESH_SOURCE_DIR (::anisomesh_test::sourceDir())
#define ANISOMESH_CLI_PATH (::anisomesh_test::cliPath())

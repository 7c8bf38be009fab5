// The only test object that holds the checkout's paths (see test_paths.h).
#include "test_paths.h"

namespace anisomesh_test {
const char* sourceDir() { return ANISOMESH_TEST_SOURCE_DIR; }
const char* cliPath() { return ANISOMESH_TEST_CLI_PATH; }
}  // namespace anisomesh_test

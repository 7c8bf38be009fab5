// The version string, compiled in from package.json by CMake (ANISOMESH_VERSION).
#include "anisomesh/core/version.h"

namespace anisomesh {

const char* version() { return ANISOMESH_VERSION; }

}  // namespace anisomesh

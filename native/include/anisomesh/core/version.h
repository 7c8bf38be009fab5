#pragma once
// The library's version (package.json's "version", the one place it is written).

namespace anisomesh {

// "MAJOR.MINOR.PATCH".
const char* version();

}  // namespace anisomesh

// libFuzzer target: the Medit .mesh reader. A parsed mesh must survive writing and
// re-reading unchanged in size (no silent change); bad text is an anisomesh::Error.
#include <cstddef>
#include <cstdint>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/medit.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const anisomesh::Mesh mesh = anisomesh::parseMedit(text);
    const anisomesh::Mesh back = anisomesh::parseMedit(anisomesh::writeMedit(mesh));
    if (back.vertexCount() != mesh.vertexCount() || back.elementCount() != mesh.elementCount() ||
        back.dimension != mesh.dimension)
      __builtin_trap();
  } catch (const anisomesh::Error&) {
  }
  return 0;
}

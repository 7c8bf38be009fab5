// libFuzzer target: the Medit .sol reader and its conversion to metrics.
#include <cstddef>
#include <cstdint>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/medit.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const anisomesh::SolData sol = anisomesh::parseSol(text);
    const anisomesh::SolData back = anisomesh::parseSol(anisomesh::writeSol(sol));
    if (back.values.size() != sol.values.size()) __builtin_trap();
    if (sol.dimension == 2) anisomesh::solToMetrics(sol, sol.count());
  } catch (const anisomesh::Error&) {
  }
  return 0;
}

// libFuzzer target: a JSON case (planar or surface) through the whole pipeline with a
// small element budget. Any anisomesh::Error is a valid outcome; anything else that
// escapes (another exception, a sanitizer report, a timeout) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/run_case.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  anisomesh::RunCaseOptions o;
  o.maxElements = 2000;  // small budget: a run must end fast, with a mesh or a coded error
  // and a small control space: the default node budget (at least 262144 nodes) lets a seed
  // such as expression_field build its full control space, 35 s under ASan (a timeout).
  o.maxControlNodes = 20000;
  try {
    const anisomesh::CaseRun run = anisomesh::runCase(text, o);
    if (run.mesh.elementCount() > 2000) __builtin_trap();  // the budget must hold
  } catch (const anisomesh::Error&) {
  }
  return 0;
}

#pragma once
// VTK XML unstructured grid (.vtu, ASCII) of a case run for ParaView, with point data
// (ref; planar runs: the final control space's metric tensor M as a 3x3 tensor, and the
// requested sizes h1 <= h2) and cell data (ref; quality: metric quality, planar in the final
// control space, surface in 3D, -1 on boundary-edge cells; planar: smallest and largest
// metric edge length per cell).
#include <string>

#include "anisomesh/io/run_case.h"

namespace anisomesh {

// The .vtu text of run.mesh with the fields above (only refs when the run has no measures).
std::string caseRunVtu(const CaseRun& run);

}  // namespace anisomesh

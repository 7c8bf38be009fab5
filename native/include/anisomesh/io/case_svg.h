#pragma once
// The .svg picture of a case run, as the CLI and the npm package draw it: elements coloured
// by metric quality (planar: in the final control space; surface: in 3D), surfaces in a 3D
// view unless uv, the surface control spaces' ellipses over the mesh when the run kept them.
#include <string>

#include "anisomesh/io/run_case.h"

namespace anisomesh {

struct CaseSvgOptions {
  bool uv = false;         // surface meshes in the parameter plane instead of 3D
  double azimuth = -1.1;   // 3D view direction, radians (the CLI's --svg-view takes degrees)
  double elevation = 0.6;  // radians
};

// The picture of run.mesh (with run.glyphs drawn over it when present).
std::string caseRunSvg(const CaseRun& run, const CaseSvgOptions& options = {});

}  // namespace anisomesh

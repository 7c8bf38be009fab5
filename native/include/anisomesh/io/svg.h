#pragma once
// SVG pictures of planar meshes (parameter plane), for READMEs and quick looks.
#include <string>
#include <vector>

#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

struct SvgOptions {
  int width = 800;                    // picture width in pixels; the height follows the aspect ratio
  double strokeWidth = 0.6;           // element edge width in pixels
  std::vector<double> elementValues;  // optional per-element value in [0, 1] (e.g. quality) to colour elements
  bool drawBoundary = true;           // boundary edges drawn thicker
};

// Writes the mesh (params if present, else points' x, y) as a standalone SVG document.
std::string writeSvg(const Mesh& mesh, const SvgOptions& options = {});

}  // namespace anisomesh

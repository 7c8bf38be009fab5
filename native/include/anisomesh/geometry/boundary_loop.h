#pragma once
// A discretized contour: what contour discretization gives and the planar mesher takes.
#include <vector>

#include "anisomesh/core/types.h"

namespace anisomesh {

// One closed polygonal contour: edge i joins points[i] and points[(i + 1) % n] and
// carries edgeRefs[i] (the Medit reference of the curve it discretizes).
struct BoundaryLoop {
  std::vector<Vec2> points;
  std::vector<int> edgeRefs;
};

}  // namespace anisomesh

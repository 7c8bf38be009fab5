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
  // The contour curve's point halfway (in its parameter) along edge i, where the all-quad
  // split puts the edge's new point; empty: the straight midpoints (no curve behind the loop).
  std::vector<Vec2> edgeMidpoints;
};

}  // namespace anisomesh

#pragma once
// Private to controlspace/: the boxes of control nodes and source pieces in the bucket
// grid (core/bucket_grid.h) with which the discrete sources and the minimum of two
// control spaces find what lies near a control node.
#include <algorithm>
#include <cmath>
#include <vector>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/bucket_grid.h"

namespace anisomesh {
namespace controlspace_internal {

using anisomesh::BucketGrid;

inline Box2 pointBox(const Vec2& p, double r) {
  Box2 b;
  b.lo = p - Vec2(r, r);
  b.hi = p + Vec2(r, r);
  return b;
}

inline Box2 pieceBox(const SourcePiece& s, double r) {
  Box2 b;
  b.lo = s.a.cwiseMin(s.b) - Vec2(r, r);
  b.hi = s.a.cwiseMax(s.b) + Vec2(r, r);
  return b;
}

}  // namespace controlspace_internal
}  // namespace anisomesh

#pragma once
// Helpers shared by the control-space tests.
#include "anisomesh/core/types.h"

namespace anisomesh::test_util {

// The rectangle [x0, x1] x [y0, y1].
inline Box2 box(double x0, double y0, double x1, double y1) {
  Box2 b;
  b.lo = Vec2(x0, y0);
  b.hi = Vec2(x1, y1);
  return b;
}

}  // namespace anisomesh::test_util

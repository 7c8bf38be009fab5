#pragma once
// Helpers shared by the geometry tests.
#include <memory>

#include "anisomesh/geometry/domain.h"

namespace anisomesh::test_util {

// The axis-aligned rectangle [x0, x1] x [y0, y1] as a counter-clockwise contour of four
// lines with refs 1 (bottom), 2 (right), 3 (top), 4 (left).
inline Contour rectangle(double x0, double y0, double x1, double y1) {
  Contour c;
  c.add(std::make_shared<LineCurve>(Vec2(x0, y0), Vec2(x1, y0), 1));
  c.add(std::make_shared<LineCurve>(Vec2(x1, y0), Vec2(x1, y1), 2));
  c.add(std::make_shared<LineCurve>(Vec2(x1, y1), Vec2(x0, y1), 3));
  c.add(std::make_shared<LineCurve>(Vec2(x0, y1), Vec2(x0, y0), 4));
  return c;
}

}  // namespace anisomesh::test_util

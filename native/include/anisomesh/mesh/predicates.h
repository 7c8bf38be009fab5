#pragma once
// Robust geometric predicates: a floating-point filter with an exact fallback on
// floating-point expansions, so that decisions that shape the topology (which side of
// a line, inside a circle) are always right, also on collinear and cocircular input.
#include "anisomesh/core/types.h"

namespace anisomesh {

// Twice the signed area of (a, b, c): > 0 counter-clockwise, < 0 clockwise, 0 collinear.
// The sign is exact; the magnitude is approximate.
double orient2d(const double* a, const double* b, const double* c);
// Same on Vec2.
inline double orient2d(const Vec2& a, const Vec2& b, const Vec2& c) { return orient2d(a.data(), b.data(), c.data()); }

// > 0 when d lies inside the circle through a, b, c (taken counter-clockwise), < 0 outside,
// 0 on it. The sign is exact (reversed when a, b, c are clockwise).
double incircle(const double* a, const double* b, const double* c, const double* d);
// Same on Vec2.
inline double incircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  return incircle(a.data(), b.data(), c.data(), d.data());
}

// The plain floating-point evaluations, for comparisons in the tests.
double orient2dNaive(const Vec2& a, const Vec2& b, const Vec2& c);
double incircleNaive(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

}  // namespace anisomesh

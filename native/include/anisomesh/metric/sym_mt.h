#pragma once
// Mt as its three distinct entries [a b; b c]: the compact layout of control nodes
// (flat arrays on the query path) and of the mesher's per-vertex metrics.
#include "anisomesh/core/types.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

// Symmetric transformation matrix Mt = [a b; b c], three doubles (cache friendly).
struct SymMt {
  double a = 1.0, b = 0.0, c = 1.0;
  // The entries of m, symmetrized.
  static SymMt from(const Mat2& m) { return {m(0, 0), 0.5 * (m(0, 1) + m(1, 0)), m(1, 1)}; }
  // Entry-wise mean of three matrices.
  static SymMt average3(const SymMt& x, const SymMt& y, const SymMt& z) {
    constexpr double k = 1.0 / 3.0;
    return {(x.a + y.a + z.a) * k, (x.b + y.b + z.b) * k, (x.c + y.c + z.c) * k};
  }
  // Entry-wise mean of two matrices.
  static SymMt average2(const SymMt& x, const SymMt& y) {
    return {0.5 * (x.a + y.a), 0.5 * (x.b + y.b), 0.5 * (x.c + y.c)};
  }
  // det(Mt).
  double det() const { return a * c - b * b; }
  // Mt v.
  Vec2 apply(const Vec2& v) const { return {a * v.x() + b * v.y(), b * v.x() + c * v.y()}; }
  // Mt^-1 v.
  Vec2 solve(const Vec2& v) const {
    const double d = det();
    return {(c * v.x() - b * v.y()) / d, (a * v.y() - b * v.x()) / d};
  }
  // Metric length |Mt v| of v.
  double length(const Vec2& v) const { return apply(v).norm(); }
};

// Mt entries of a metric.
inline SymMt toSymMt(const Metric& m) { return SymMt::from(m.transform()); }

// The metric whose Mt has these entries (no validation: values come from SPD metrics).
inline Metric toMetric(const SymMt& s) {
  Mat2 t;
  t << s.a, s.b, s.b, s.c;
  return Metric::fromTransformUnchecked(t);
}

}  // namespace anisomesh

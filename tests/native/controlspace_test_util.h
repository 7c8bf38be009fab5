#pragma once
// Helpers shared by the control-space tests.
#include <algorithm>
#include <cmath>
#include <random>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/core/types.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh::test_util {

// The rectangle [x0, x1] x [y0, y1].
inline Box2 box(double x0, double y0, double x1, double y1) { return Box2{Vec2(x0, y0), Vec2(x1, y1)}; }

// The analytic boundary layer along y = 0.5: 0.001 across at the line, growing by 0.1 per
// unit of distance, 0.1 along x (aspect ratio 100 at the layer).
inline Metric boundaryLayer(const Vec2& p) { return Metric::fromSizes(0.0, 0.1, 0.001 + 0.1 * std::abs(p.y() - 0.5)); }

// Largest relative error |l / l_exact - 1| of cs's metric length against `exact`, over
// `count` random points of the unit square with random directions (fixed seed).
template <class ExactMetric>
double worstLengthError(const ControlSpace& cs, ExactMetric&& exact, int count = 10000) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0), ang(0.0, 2 * M_PI);
  double worst = 0.0;
  for (int k = 0; k < count; ++k) {
    const Vec2 p(u(rng), u(rng));
    const Vec2 d(std::cos(ang(rng)), std::sin(ang(rng)));
    worst = std::max(worst, std::abs(cs.metricAt(p).length(d) / exact(p).length(d) - 1.0));
  }
  return worst;
}

}  // namespace anisomesh::test_util

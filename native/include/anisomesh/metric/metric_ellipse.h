#pragma once
// The unit ball of a metric as a closed polyline, for drawing (control space glyphs, the
// package's metricEllipse): the points x with |Mt (x - c)| = scale.
#include <vector>

#include "anisomesh/core/types.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

// segments points of {x : |Mt (x - center)| = scale}, from angle 0 counter-clockwise
// (x = center + scale Mt^-1 (cos a, sin a)); InvalidArgument unless segments is in [3, 100000].
std::vector<Vec2> metricEllipse(const Metric& m, const Vec2& center, int segments, double scale = 1.0);

}  // namespace anisomesh

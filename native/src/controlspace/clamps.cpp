// Size clamps of a metric and of a whole control space (hmin, hmax).
#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"

namespace anisomesh {

Metric clampMetricSizes(const Metric& m, double hmin, double hmax) {
  const MetricSizes s = m.sizes();
  const double h1 = std::clamp(s.h1, hmin, hmax), h2 = std::clamp(s.h2, hmin, hmax);
  if (h1 == s.h1 && h2 == s.h2) return m;
  return Metric::fromSizes(s.alpha, h1, h2);
}

void clampSizes(AdaptiveControlSpace& cs, double hmin, double hmax) {
  require(std::isfinite(hmin) && hmin > 0.0 && !(hmax < hmin), ErrorCode::InvalidArgument,
          "size clamps need 0 < hmin <= hmax");
  for (int i = 0; i < cs.nodeCount(); ++i)
    if (cs.nodeIsFree(i)) cs.setNodeMetric(i, clampMetricSizes(cs.nodeMetric(i), hmin, hmax));
  cs.applyConstraints();
}

}  // namespace anisomesh

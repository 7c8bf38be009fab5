#include "anisomesh/metric/metric_ellipse.h"

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {

std::vector<Vec2> metricEllipse(const Metric& m, const Vec2& center, int segments, double scale) {
  require(segments >= 3 && segments <= 100000, ErrorCode::InvalidArgument, "ellipse segments must be in [3, 100000]");
  const Mat2 inv = m.transform().inverse();
  std::vector<Vec2> out;
  out.reserve(static_cast<size_t>(segments));
  for (int i = 0; i < segments; ++i) {
    const double a = 6.283185307179586 * i / segments;
    out.push_back(center + scale * (inv * Vec2(pm::cos(a), pm::sin(a))));
  }
  return out;
}

}  // namespace anisomesh

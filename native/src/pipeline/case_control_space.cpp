#include "anisomesh/pipeline/case_control_space.h"

#include <algorithm>
#include <cmath>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {
// Not M_PI: strict C++17 headers (libc++/musl under Emscripten) need not define it.
constexpr double kPiValue = 3.14159265358979323846;
}  // namespace
namespace {

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::min(1.0, std::max(0.0, (p - a).dot(ab) / l2)) : 0.0;
  return (p - (a + t * ab)).norm();
}

// A layer field: size hTangent along direction alpha, across it h0 at distance 0 growing
// linearly to hTangent at the layer thickness, then both growing with the slope.
bool layerMetric(const AnalyticFieldSpec& f, double alpha, double d, double slope, Metric* out) {
  if (d <= f.thickness) {
    const double hn = f.h0 + (f.hTangent - f.h0) * d / f.thickness;
    *out = Metric::fromSizes(alpha, f.hTangent, hn);
    return true;
  }
  if (slope < 0) return false;
  const double h = f.hTangent + slope * (d - f.thickness);
  *out = Metric::isotropic(h);
  return true;
}

}  // namespace


bool sourceMetricAt(const SourceSpec& s, const Vec2& p, double slope, Metric* out) {
  switch (s.type) {
    case SourceType::Radial:
    case SourceType::Segment: {
      const double d = s.type == SourceType::Radial ? (p - s.center).norm() : distanceToSegment(p, s.p1, s.p2);
      if (d <= s.radius) {
        *out = Metric::fromSizes(s.metric.alpha, s.metric.h1, s.metric.h2);
        return true;
      }
      if (slope < 0) return false;
      // Both sizes grow by the same amount, so the anisotropy fades with distance.
      const double grow = slope * (d - s.radius);
      *out = Metric::fromSizes(s.metric.alpha, s.metric.h1 + grow, s.metric.h2 + grow);
      return true;
    }
    case SourceType::Analytic: {
      const AnalyticFieldSpec& f = s.analytic;
      if (f.field == "point") {
        *out = Metric::isotropic(f.h0 + f.growth * (p - f.center).norm());
        return true;
      }
      if (f.field == "boundary_layer") {
        const Vec2 t = (f.p2 - f.p1).normalized();
        const Vec2 n(-t.y(), t.x());
        return layerMetric(f, std::atan2(t.y(), t.x()), std::abs(n.dot(p - f.p1)), slope, out);
      }
      if (f.field == "shear_layer_circle") {
        const Vec2 r = p - f.center;
        const double theta = std::atan2(r.y(), r.x());
        return layerMetric(f, theta + kPiValue / 2, std::abs(r.norm() - f.radius), slope, out);
      }
      throw Error(ErrorCode::InvalidArgument, "unknown analytic field '" + f.field + "'");
    }
  }
  return false;
}

MetricFunction caseMetricFunction(const CaseSpec& spec) {
  const double hmin = spec.controlSpace.hmin, hmax = spec.controlSpace.hmax;
  const double slope = spec.controlSpace.gradation ? gradationSlope(*spec.controlSpace.gradation) : -1.0;
  const std::vector<SourceSpec> sources = spec.sources;
  const Metric background = Metric::isotropic(hmax);
  return [=](const Vec2& p) {
    Metric m = background;
    Metric s;
    for (const SourceSpec& src : sources)
      if (sourceMetricAt(src, p, slope, &s)) m = intersect(m, s);
    if (hmin > 0) {
      // Clamp to hmin; the background already bounds every size by hmax.
      const MetricSizes z = m.sizes();
      if (z.h1 < hmin) m = Metric::fromSizes(z.alpha, hmin, std::max(z.h2, hmin));
    }
    return m;
  };
}

std::unique_ptr<ControlSpace> buildCaseControlSpace(const CaseSpec& spec) {
  Box2 box = domainBounds(spec.domain);
  const Vec2 margin = Vec2::Constant(0.01 * std::max(box.size().norm(), 1e-12));
  box.lo -= margin;
  box.hi += margin;
  return std::make_unique<AnalyticControlSpace>(box, caseMetricFunction(spec));
}

}  // namespace anisomesh

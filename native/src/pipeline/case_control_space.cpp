#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/core/number_text.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/geometry/expression.h"

namespace anisomesh {
namespace {
// Not M_PI: strict C++17 headers (libc++/musl under Emscripten) need not define it.
constexpr double kPiCase = 3.14159265358979323846;

// Source sizes near discrete sources: elements of a quarter of the source's extent keep
// the source's edge sharp (without gradation the paper's fig. 6 shows abrupt jumps).
constexpr double kSourceSizeFactor = 0.25;

// A layer field: size hTangent along direction alpha, across it h0 at distance 0 growing
// linearly to hTangent at the layer thickness; nothing beyond (the hmax default and
// the gradation smoothing of the structure take over).
bool layerMetric(const AnalyticFieldSpec& f, double alpha, double d, Metric* out) {
  if (d > f.thickness) return false;
  const double hn = f.h0 + (f.hTangent - f.h0) * d / f.thickness;
  *out = Metric::fromSizes(alpha, f.hTangent, hn);
  return true;
}

// One analytic field as a function; false where the field does not act.
using CaseFieldFunction = std::function<bool(const Vec2&, Metric*)>;

CaseFieldFunction fieldFunction(const AnalyticFieldSpec& f) {
  if (f.field == "point")
    return [f](const Vec2& p, Metric* out) {
      *out = Metric::isotropic(f.h0 + f.growth * (p - f.center).norm());
      return true;
    };
  if (f.field == "boundary_layer")
    return [f](const Vec2& p, Metric* out) {
      const Vec2 t = (f.p2 - f.p1).normalized();
      const Vec2 n(-t.y(), t.x());
      return layerMetric(f, pm::atan2(t.y(), t.x()), std::abs(n.dot(p - f.p1)), out);
    };
  if (f.field == "shear_layer_circle")
    return [f](const Vec2& p, Metric* out) {
      const Vec2 r = p - f.center;
      return layerMetric(f, pm::atan2(r.y(), r.x()) + kPiCase / 2, std::abs(r.norm() - f.radius), out);
    };
  if (f.field == "expression") {
    ExpressionOptions o;
    o.uName = "x";
    o.vName = "y";
    o.name = f.path + ".alpha";
    const Expression alpha = Expression::parse(f.alpha, o);
    o.name = f.path + ".h1";
    const Expression h1 = Expression::parse(f.h1, o);
    o.name = f.path + ".h2";
    const Expression h2 = Expression::parse(f.h2, o);
    const std::string path = f.path;
    return [alpha, h1, h2, path](const Vec2& p, Metric* out) {
      const double a = alpha.value(p.x(), p.y()), s1 = h1.value(p.x(), p.y()), s2 = h2.value(p.x(), p.y());
      if (!(std::isfinite(a) && std::isfinite(s1) && std::isfinite(s2) && s1 > 0 && s2 > 0))
        throw Error(ErrorCode::InvalidMetric,
                    path + ": at " + formatPoint(p) + " the formulas give alpha = " + numberText(a) +
                        ", h1 = " + numberText(s1) + ", h2 = " + numberText(s2) + " (sizes must be finite and > 0)");
      *out = Metric::fromSizes(a, s1, s2);
      return true;
    };
  }
  throw Error(ErrorCode::InvalidArgument, "unknown analytic field '" + f.field + "'");
}

}  // namespace

MetricFunction caseAnalyticMetric(const CaseSpec& spec) {
  std::vector<CaseFieldFunction> fields;
  for (const SourceSpec& s : spec.sources)
    if (s.type == SourceType::Analytic) fields.push_back(fieldFunction(s.analytic));
  const double hmin = spec.controlSpace.hmin;
  const Metric background = Metric::isotropic(spec.controlSpace.hmax);
  return [fields, hmin, background](const Vec2& p) {
    Metric m = background;
    Metric s;
    for (const CaseFieldFunction& f : fields)
      if (f(p, &s)) m = intersect(m, s);
    // The background already bounds every size by hmax.
    return hmin > 0 ? clampMetricSizes(m, hmin, std::numeric_limits<double>::infinity()) : m;
  };
}

std::vector<MetricSource> caseDiscreteSources(const CaseSpec& spec) { return discreteSources(spec.sources); }

ControlSpaceSpec caseControlSpaceSpec(const CaseSpec& spec) {
  const CaseControlSpaceSpec& c = spec.controlSpace;
  ControlSpaceSpec s;
  s.kind = c.kind == "background" ? ControlSpaceKind::BackgroundMesh : ControlSpaceKind::Quadtree;
  Box2 box = domainBounds(spec.domain);
  const Vec2 margin = Vec2::Constant(0.01 * std::max(box.size().norm(), 1e-12));
  box.lo -= margin;
  box.hi += margin;
  s.box = box;
  s.interpolation =
      c.interpolation == "serendipity" ? QuadtreeInterpolation::Serendipity : QuadtreeInterpolation::Bilinear;
  // Barycentric by default: a continuous field; eq. 11 on request.
  s.backgroundInterpolation = c.interpolation == "inverse_distance" ? BackgroundInterpolation::InverseSquaredDistance
                                                                    : BackgroundInterpolation::Linear;
  s.analytic = caseAnalyticMetric(spec);
  s.refineThreshold = c.refineThreshold;
  if (c.maxLevel > 0) {
    s.maxLevel = c.maxLevel;
  } else {
    // Elements need not get smaller than the smallest size the case allows.
    const double side = std::max(box.size().x(), box.size().y());
    const double h = c.hmin > 0 ? c.hmin : c.hmax / 100.0;
    // (decided in double: side / h may overflow, and a huge or NaN level must not reach int)
    const double level = std::ceil(pm::log2(side / h));
    s.maxLevel = level > s.initialLevel ? (level < 14.0 ? static_cast<int>(level) : 14) : s.initialLevel;
  }
  return s;
}

void finishCaseControlSpace(AdaptiveControlSpace& cs, const CaseSpec& spec) {
  const CaseControlSpaceSpec& c = spec.controlSpace;
  clampSizes(cs, c.hmin > 0 ? c.hmin : std::numeric_limits<double>::min(), c.hmax);
  if (c.gradation) {
    GradationOptions g;
    g.ratio = *c.gradation;
    smoothGradation(cs, g);
  }
}

void addCaseSources(AdaptiveControlSpace& cs, const CaseSpec& spec, const std::vector<MetricSource>& sources) {
  if (!sources.empty()) {
    DiscreteInsertionOptions o;
    o.source.sizeFactor = kSourceSizeFactor;
    o.fallbackMetric = Metric::isotropic(spec.controlSpace.hmax);
    insertSources(cs, sources, o);
  }
  finishCaseControlSpace(cs, spec);
}

std::unique_ptr<AdaptiveControlSpace> buildCaseControlSpace(const CaseSpec& spec,
                                                            const std::function<bool(double)>& progress) {
  ControlSpaceSpec s = caseControlSpaceSpec(spec);
  s.limits.maxNodes = spec.options.maxControlNodes > 0 ? spec.options.maxControlNodes
                                                       : controlSpaceNodeBudget(spec.options.maxElements);
  s.limits.progress = progress;
  std::unique_ptr<AdaptiveControlSpace> cs = buildAdaptiveControlSpace(s);
  addCaseSources(*cs, spec, caseDiscreteSources(spec));
  return cs;
}

}  // namespace anisomesh

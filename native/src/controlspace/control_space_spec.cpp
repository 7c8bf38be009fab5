#include "anisomesh/controlspace/control_space_spec.h"

#include <cmath>
#include <limits>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/query_cache.h"
#include "anisomesh/core/error.h"

namespace anisomesh {

std::unique_ptr<AdaptiveControlSpace> buildAdaptiveControlSpace(const ControlSpaceSpec& spec) {
  require(spec.gradation == 0.0 || (std::isfinite(spec.gradation) && spec.gradation >= 1.0), ErrorCode::InvalidArgument,
          "gradation ratio must be 0 (off) or >= 1");
  require(std::isfinite(spec.hmin) && spec.hmin >= 0.0 && !std::isnan(spec.hmax) && spec.hmax >= 0.0 &&
              (spec.hmax == 0.0 || spec.hmax >= spec.hmin),
          ErrorCode::InvalidArgument, "size clamps need 0 <= hmin <= hmax (0 = no clamp)");
  require(std::isfinite(spec.refineThreshold) && spec.refineThreshold > 0.0, ErrorCode::InvalidArgument,
          "refineThreshold must be > 0");
  std::unique_ptr<AdaptiveControlSpace> cs;
  if (spec.kind == ControlSpaceKind::Quadtree) {
    QuadtreeOptions o;
    o.initialLevel = spec.initialLevel;
    o.maxLevel = spec.maxLevel;
    o.interpolation = spec.interpolation;
    cs = std::make_unique<QuadtreeControlSpace>(spec.box, o);
  } else {
    require(spec.initialLevel >= 0 && spec.initialLevel <= 10, ErrorCode::InvalidArgument,
            "initialLevel must be in [0, 10]");
    BackgroundMeshOptions o;
    o.initialGrid = 1 << spec.initialLevel;
    o.maxLevel = spec.maxLevel;
    o.interpolation = spec.backgroundInterpolation;
    cs = std::make_unique<BackgroundMeshControlSpace>(spec.box, o);
  }
  cs->setLimits(spec.limits);
  const Metric fallback = spec.defaultMetric ? *spec.defaultMetric : Metric::isotropic(0.1 * spec.box.size().norm());
  bool any = false;
  if (!spec.sources.empty()) {
    DiscreteInsertionOptions o;
    o.fallbackMetric = fallback;
    insertSources(*cs, spec.sources, o);
    for (int i = 0; i < cs->nodeCount() && !any; ++i) any = cs->nodeIsInitialized(i);
  }
  if (spec.analytic) {
    ContinuousInsertionOptions o;
    o.threshold = spec.refineThreshold;
    o.minMetricSize = spec.refineMinMetricSize;
    o.concurrent = spec.analyticConcurrent;
    o.domain = spec.analyticDomain;
    insertMetricFunction(*cs, spec.analytic, o);
    any = true;
  }
  if (!any) {
    for (int i = 0; i < cs->nodeCount(); ++i)
      if (cs->nodeIsFree(i)) cs->setNodeMetric(i, fallback);
    cs->applyConstraints();
  }
  if (spec.hmin > 0.0 || spec.hmax > 0.0)
    clampSizes(*cs, spec.hmin > 0.0 ? spec.hmin : std::numeric_limits<double>::min(),
               spec.hmax > 0.0 ? spec.hmax : std::numeric_limits<double>::infinity());
  if (spec.gradation > 0.0) {
    GradationOptions g;
    g.ratio = spec.gradation;
    smoothGradation(*cs, g);
  }
  return cs;
}

std::unique_ptr<ControlSpace> buildControlSpace(const ControlSpaceSpec& spec) {
  require(std::isfinite(spec.cacheTolerance) && spec.cacheTolerance >= 0.0, ErrorCode::InvalidArgument,
          "cacheTolerance must be finite and >= 0");
  std::unique_ptr<AdaptiveControlSpace> cs = buildAdaptiveControlSpace(spec);
  if (spec.cacheTolerance > 0.0) {
    QueryCacheOptions o;
    o.tolerance = spec.cacheTolerance;
    return std::make_unique<CachedControlSpace>(std::move(cs), o);
  }
  return cs;
}

}  // namespace anisomesh

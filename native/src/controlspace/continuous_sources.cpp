// Continuous metric sources: a metric function sampled at the control nodes, the structure
// refined where the metric varies (section 2.2).
#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"

namespace anisomesh {

namespace {

bool elementNodesDiffer(const AdaptiveControlSpace& cs, const ControlElement& e, double threshold) {
  for (int i = 0; i < e.nodeCount; ++i)
    for (int j = i + 1; j < e.nodeCount; ++j)
      if (difference(cs.nodeMetric(e.nodes[i]), cs.nodeMetric(e.nodes[j])) > threshold) return true;
  return false;
}

}  // namespace

int refineWhereMetricsDiffer(AdaptiveControlSpace& cs, double threshold) {
  require(threshold >= 0.0, ErrorCode::InvalidArgument, "refinement threshold must be >= 0");
  const int before = cs.elementCount();
  cs.refine([&](const ControlElement& e) { return elementNodesDiffer(cs, e, threshold); }, nullptr);
  return cs.elementCount() - before;
}

void insertMetricFunction(AdaptiveControlSpace& cs, const MetricFunction& f,
                          const ContinuousInsertionOptions& options) {
  require(static_cast<bool>(f), ErrorCode::InvalidArgument, "metric function is empty");
  require(options.threshold > 0.0, ErrorCode::InvalidArgument, "continuous insertion threshold must be > 0");
  const double sampleThreshold = options.sampleThreshold < 0.0 ? options.threshold : options.sampleThreshold;
  bool fresh = true;
  for (int i = 0; i < cs.nodeCount(); ++i)
    if (cs.nodeIsFree(i) && cs.nodeIsInitialized(i)) fresh = false;
  // The field before insertion: new nodes and samples compare against min(original, f),
  // not against an interpolation of already intersected values (which would compound).
  std::unique_ptr<AdaptiveControlSpace> original;
  if (!fresh) original = cs.clone();
  auto target = [&](const Vec2& p) {
    const Metric v = f(p);
    return fresh ? v : intersect(original->metricAt(p), v);
  };
  auto setFromFunction = [&](int first, int last) {
    for (int i = first; i < last; ++i) {
      if (!cs.nodeIsFree(i)) continue;
      const Vec2& p = cs.nodePosition(i);
      cs.setNodeMetric(i, fresh || !cs.nodeIsInitialized(i) ? f(p) : target(p));
    }
  };
  setFromFunction(0, cs.nodeCount());
  cs.applyConstraints();
  cs.refine(
      [&](const ControlElement& e) {
        if (elementNodesDiffer(cs, e, options.threshold)) return true;
        if (!options.checkSamples) return false;
        for (int k = 0; k < e.sampleCount; ++k)
          if (difference(cs.metricAt(e.samples[k]), target(e.samples[k])) > sampleThreshold) return true;
        return false;
      },
      setFromFunction);
}

}  // namespace anisomesh

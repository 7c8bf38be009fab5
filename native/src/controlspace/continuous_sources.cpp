// Continuous metric sources: a metric function sampled at the control nodes, the structure
// refined where the metric varies (section 2.2).
#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "spatial_order.h"

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
  std::vector<Metric> values;
  std::vector<Vec2> positions;
  auto setFromFunction = [&](int first, int last) {
    if (options.concurrent && fresh) {
      // f's values computed in parallel chunks, in the Z-order of the nodes (f's data stay
      // in cache from a node to its neighbour), stored in node order (same result).
      values.resize(size_t(last - first));
      positions.resize(values.size());
      for (size_t k = 0; k < positions.size(); ++k) positions[k] = cs.nodePosition(first + int(k));
      const std::vector<int> order = controlspace_internal::zOrder(positions);
      parallelChunks(values.size(), 1024, [&](size_t, size_t b, size_t e) {
        for (size_t k = b; k < e; ++k) {
          const int i = first + order[k];
          if (cs.nodeIsFree(i)) values[size_t(order[k])] = f(cs.nodePosition(i));
        }
      });
      for (int i = first; i < last; ++i)
        if (cs.nodeIsFree(i)) cs.setNodeMetric(i, values[size_t(i - first)]);
      return;
    }
    for (int i = first; i < last; ++i) {
      if (!cs.nodeIsFree(i)) continue;
      const Vec2& p = cs.nodePosition(i);
      cs.setNodeMetric(i, fresh || !cs.nodeIsInitialized(i) ? f(p) : target(p));
    }
  };
  // The smallest size requested at the element's nodes (1 / the largest eigenvalue of Mt).
  auto smallestNodeSize = [&](const ControlElement& e) {
    double h = std::numeric_limits<double>::infinity();
    for (int k = 0; k < e.nodeCount; ++k) {
      const SymMt& m = cs.nodeMt(e.nodes[k]);
      h = std::min(h, 1.0 / (0.5 * (m.a + m.c) + std::hypot(0.5 * (m.a - m.c), m.b)));
    }
    return h;
  };
  setFromFunction(0, cs.nodeCount());
  cs.applyConstraints();
  const ElementPredicate split = [&](const ControlElement& e) {
    if (options.domain && !options.domain(e.box)) return false;
    if (options.minMetricSize > 0.0 && e.size < options.minMetricSize * smallestNodeSize(e)) return false;
    if (elementNodesDiffer(cs, e, options.threshold)) return true;
    if (!options.checkSamples) return false;
    for (int k = 0; k < e.sampleCount; ++k)
      if (difference(cs.elementSampleMetric(e, k), target(e.samples[k])) > sampleThreshold) return true;
    return false;
  };
  // A concurrent f on a fresh structure: the predicate only reads (f, cs's queries, the
  // domain test), so elements may be judged in parallel (the same splits).
  if (options.concurrent && fresh)
    cs.refineConcurrently(split, setFromFunction);
  else
    cs.refine(split, setFromFunction);
}

}  // namespace anisomesh

#pragma once
// The abstract ControlSpace of the paper (section 2): answers, for any point of a 2D
// domain or of a patch's parameter domain, the metric the mesh must follow. The mesher
// only ever talks to this interface.
#include <functional>
#include <memory>

#include "anisomesh/core/types.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

class ControlSpace {
 public:
  virtual ~ControlSpace() = default;
  // The requested metric at p (parameter-space coordinates).
  virtual Metric metricAt(const Vec2& p) const = 0;
  // metricAt(p), the same value; hint (the caller's own, -1 at first) lets a structure that
  // searches for p start where the caller's previous query ended (callers asking in
  // spatial order, such as the mesher).
  virtual Metric metricAtNear(const Vec2& p, int& /*hint*/) const { return metricAt(p); }
  // The parameterization matrix Mp at p (section 4.3); identity on planar domains.
  virtual Mat2 parameterizationAt(const Vec2& /*p*/) const { return Mat2::Identity(); }
  // The rectangle the control space is defined on.
  virtual Box2 bounds() const = 0;
  // Whether several threads may query it at once (the parallel stages ask; see
  // controlspace/concurrency.h). False unless a structure knows its queries are safe.
  virtual bool concurrentQueries() const { return false; }
  // Whether its queries are tallied (a report counts them): queries that may be thrown
  // away (work done ahead on a spare thread) would make the tally depend on the threads.
  virtual bool countsQueries() const { return false; }
};

// The same metric everywhere.
class UniformControlSpace : public ControlSpace {
 public:
  UniformControlSpace(const Box2& bounds, const Metric& metric) : bounds_(bounds), metric_(metric) {}
  Metric metricAt(const Vec2&) const override { return metric_; }
  Box2 bounds() const override { return bounds_; }

 private:
  Box2 bounds_;
  Metric metric_;
};

// A continuous metric given as a function of the point (analytic source).
using MetricFunction = std::function<Metric(const Vec2&)>;

// Evaluates an analytic metric function at every query.
class AnalyticControlSpace : public ControlSpace {
 public:
  AnalyticControlSpace(const Box2& bounds, MetricFunction f) : bounds_(bounds), f_(std::move(f)) {}
  Metric metricAt(const Vec2& p) const override { return f_(p); }
  Box2 bounds() const override { return bounds_; }
  const MetricFunction& function() const { return f_; }

 private:
  Box2 bounds_;
  MetricFunction f_;
};

}  // namespace anisomesh

#pragma once
// Query cache (section 4): the mesher asks for the metric at points that are often close
// to the previous one; when the new point is within `tolerance` of the last query point
// measured in the last metric (|Mt_last (p - p_last)| < tolerance), the last metric is
// returned without locating and interpolating again.
//
// NOT thread-safe: the cache mutates on every query (through const metricAt). Use one
// CachedControlSpace per thread (they may share the underlying control space, whose
// queries are const and safe to run concurrently).
#include <memory>

#include "anisomesh/controlspace/control_space.h"

namespace anisomesh {

struct QueryCacheOptions {
  double tolerance = 0.05;  // metric-space distance below which the last metric is reused
};

class CachedControlSpace : public ControlSpace {
 public:
  // Wraps a control space that must outlive the cache. Throws InvalidArgument for a
  // negative or non-finite tolerance.
  CachedControlSpace(const ControlSpace& inner, const QueryCacheOptions& options = {});
  // Wraps and owns a control space.
  CachedControlSpace(std::unique_ptr<ControlSpace> inner, const QueryCacheOptions& options = {});

  // The last metric when p is close to the last query point in its metric, else a new query.
  Metric metricAt(const Vec2& p) const override;
  Mat2 parameterizationAt(const Vec2& p) const override { return inner_->parameterizationAt(p); }
  Box2 bounds() const override { return inner_->bounds(); }

  // The wrapped control space.
  const ControlSpace& inner() const { return *inner_; }
  // Queries answered from the cache / passed to the inner control space.
  long long hits() const { return hits_; }
  long long misses() const { return misses_; }
  // Forgets the last query (call after the inner control space changed).
  void reset() const { valid_ = false; }

 private:
  std::unique_ptr<ControlSpace> owned_;
  const ControlSpace* inner_;
  double tol2_;
  mutable bool valid_ = false;
  mutable Vec2 last_{0.0, 0.0};
  mutable Metric lastMetric_;
  mutable long long hits_ = 0, misses_ = 0;
};

}  // namespace anisomesh

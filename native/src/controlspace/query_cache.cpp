#include "anisomesh/controlspace/query_cache.h"

#include <cmath>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

double checkedTolerance(const QueryCacheOptions& o) {
  require(std::isfinite(o.tolerance) && o.tolerance >= 0.0, ErrorCode::InvalidArgument,
          "query cache tolerance must be finite and >= 0");
  return o.tolerance * o.tolerance;
}

}  // namespace

CachedControlSpace::CachedControlSpace(const ControlSpace& inner, const QueryCacheOptions& options)
    : inner_(&inner), tol2_(checkedTolerance(options)) {}

CachedControlSpace::CachedControlSpace(std::unique_ptr<ControlSpace> inner, const QueryCacheOptions& options)
    : owned_(std::move(inner)), inner_(owned_.get()), tol2_(checkedTolerance(options)) {
  require(inner_ != nullptr, ErrorCode::InvalidArgument, "query cache needs a control space");
}

Metric CachedControlSpace::metricAt(const Vec2& p) const {
  if (valid_ && lastMetric_.apply(p - last_).squaredNorm() < tol2_) {
    ++hits_;
    return lastMetric_;
  }
  ++misses_;
  lastMetric_ = inner_->metricAt(p);
  last_ = p;
  valid_ = true;
  return lastMetric_;
}

}  // namespace anisomesh

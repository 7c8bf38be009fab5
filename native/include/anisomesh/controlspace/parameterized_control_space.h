#pragma once
// Section 4.3: the parameterization matrix Mp of a surface patch stored in the control
// nodes and interpolated "in precisely the same way" as the metric. A patch's control space
// is built in its parameter plane, where sources, the minimum and gradation act on the
// pulled-back metric M = Mp Mt^2 Mp (Mt: the transformation in the tangent plane, in the
// orthonormal frame J Mp^-1). This view of a finished structure splits every node's M into
// Mt and Mp and answers queries from them: Mp interpolated from the nodes (Stored) or
// computed from the surface at the query (Computed); Folded is the structure itself.
#include <functional>
#include <vector>

#include "anisomesh/controlspace/adaptive_control_space.h"

namespace anisomesh {

enum class ParameterizationStorage {
  Folded,    // the nodes hold the (u, v) metric M itself: no Mp at a query
  Stored,    // the nodes hold Mt and Mp, both interpolated (section 4.3)
  Computed,  // the nodes hold Mt; Mp is computed from the surface at every query
};

// Mp at a point of the parameter plane (symmetric positive definite; may throw).
using ParameterizationFunction = std::function<Mat2(const Vec2&)>;

class ParameterizedControlSpace : public ControlSpace {
 public:
  // The view of space (which must outlive it and not change while it is used): Mp at every
  // node from mp, Mt = sqrt(Mp^-1 M Mp^-1). Hanging nodes take their masters' weighted
  // Mt and Mp, so the interpolated fields stay continuous. Where mp throws or is singular
  // the node keeps M with Mp = I. storage: Stored or Computed (InvalidArgument otherwise).
  ParameterizedControlSpace(const AdaptiveControlSpace& space, ParameterizationFunction mp,
                            ParameterizationStorage storage);

  // Mp Mt^2 Mp at p, Mt interpolated from the nodes, Mp as the storage says.
  Metric metricAt(const Vec2& p) const override;
  // Mp at p: interpolated from the nodes (Stored) or computed (Computed).
  Mat2 parameterizationAt(const Vec2& p) const override;
  Box2 bounds() const override { return space_.bounds(); }
  // As the structure's: mp must then be safe to call from several threads (a surface's
  // evaluation is: it keeps no state).
  bool concurrentQueries() const override { return space_.concurrentQueries(); }

  ParameterizationStorage storage() const { return storage_; }
  // Mt of node i (in the tangent plane's frame J Mp^-1).
  const SymMt& nodeTangentMt(int i) const { return tangent_[size_t(i)]; }

 private:
  const AdaptiveControlSpace& space_;
  ParameterizationFunction mp_;
  ParameterizationStorage storage_;
  std::vector<SymMt> tangent_, param_;
};

}  // namespace anisomesh

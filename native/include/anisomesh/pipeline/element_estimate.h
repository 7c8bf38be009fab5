#pragma once
// Estimates of a run's output made from the metric before the work, so that a request far
// beyond the element budget stops at once (ElementBudgetExceeded naming the stage and the
// estimate) instead of after discretizing and meshing most of it.
#include <cstdint>

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/geometry/domain.h"

namespace anisomesh {

struct ElementEstimateOptions {
  // The estimate may exceed the budget by this factor before the run is refused: it is an
  // estimate (the metric is sampled once per control element), and the mesher checks the
  // budget again, exactly, once the boundary is discretized.
  double slack = 2.0;
};

// Triangles a unit mesh of domain under cs needs: the metric area of the domain (the
// integral of sqrt(det M), sampled at the centre of every control element inside the
// domain) over the area of a unit equilateral triangle, sqrt(3)/4. Never overflows:
// computed in double, infinite when the metric is.
double estimateElementCount(const Domain& domain, const AdaptiveControlSpace& cs);

// An upper bound of estimateElementCount(domain, cs) for any domain inside cs's bounds,
// from the node values alone (no query): a query interpolates a leaf's node Mt with
// weights whose absolute values sum to at most 3, so sqrt(det M) <= (4 max ||Mt_i||)^2
// with margin, over the area of the bounds (the control elements tile them).
double elementCountBound(const AdaptiveControlSpace& cs);

// Throws ElementBudgetExceeded, naming stage and the estimate, when
// estimateElementCount(domain, cs) > options.slack * maxElements.
void checkElementEstimate(const Domain& domain, const AdaptiveControlSpace& cs, std::int64_t maxElements,
                          const char* stage, const ElementEstimateOptions& options = {});

}  // namespace anisomesh

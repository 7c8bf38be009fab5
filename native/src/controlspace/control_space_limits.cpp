// Bounds on control-space construction: the node budget checked before each batch of
// splits, and the time-throttled progress callback that makes refinement cancellable.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/core/error.h"

namespace anisomesh {

std::int64_t controlSpaceNodeBudget(std::int64_t maxElements) {
  return std::max<std::int64_t>(0, maxElements) / 64 + 262144;
}

void AdaptiveControlSpace::checkRefinementEstimate(std::int64_t splits, double nodesPerSplit) const {
  // In double: a count times a factor never overflows there.
  const double estimate = double(nodeCount()) + double(splits) * nodesPerSplit;
  if (estimate <= double(limits_.maxNodes)) return;
  std::ostringstream os;
  os.precision(3);
  os << "control-space refinement: the next " << splits << " splits would make about " << estimate << " nodes (now "
     << nodeCount() << "), above the node budget of " << limits_.maxNodes
     << " (derived from the element budget; raise maxElements or the control-space node budget)";
  throw Error(ErrorCode::ElementBudgetExceeded, os.str());
}

void AdaptiveControlSpace::refinementTick() const {
  if (!limits_.progress || (++ticks_ & 255u) != 0) return;
  const std::int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
  if (lastTickNs_ != 0 && now - lastTickNs_ < 5000000) return;
  lastTickNs_ = now;
  require(limits_.progress(0.0), ErrorCode::Cancelled, "control-space construction cancelled");
}

}  // namespace anisomesh

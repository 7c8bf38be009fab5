#pragma once
// Private to controlspace/: an order of points along a Z-order (Morton) curve, in which a
// batch of independent queries (the verdicts on a refinement round's elements, the values
// at its new nodes) is evaluated, so that neighbours follow each other and the data their
// queries read (a carrier mesh's triangles) are still in cache. Only the evaluation order
// changes: the results are stored per item, whatever the order.
#include <vector>

#include "anisomesh/core/types.h"

namespace anisomesh {
namespace controlspace_internal {

// The indices of points along a Z-order curve over their box (ties: increasing index).
std::vector<int> zOrder(const std::vector<Vec2>& points);

}  // namespace controlspace_internal
}  // namespace anisomesh

#include "anisomesh/controlspace/minimum_control_space.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "anisomesh/core/error.h"

namespace anisomesh {

MinimumControlSpace::MinimumControlSpace(std::vector<std::shared_ptr<const ControlSpace>> inputs)
    : inputs_(std::move(inputs)) {
  require(!inputs_.empty(), ErrorCode::InvalidArgument, "minimum control space needs at least one input");
  for (const auto& cs : inputs_)
    require(cs != nullptr, ErrorCode::InvalidArgument, "minimum control space input is null");
  bounds_ = inputs_.front()->bounds();
  for (const auto& cs : inputs_) {
    const Box2 b = cs->bounds();
    bounds_.lo = bounds_.lo.cwiseMax(b.lo);
    bounds_.hi = bounds_.hi.cwiseMin(b.hi);
  }
  require(bounds_.lo.x() <= bounds_.hi.x() && bounds_.lo.y() <= bounds_.hi.y(), ErrorCode::InvalidDomain,
          "minimum control space inputs have no common rectangle");
}

bool MinimumControlSpace::concurrentQueries() const {
  for (const auto& in : inputs_)
    if (!in->concurrentQueries()) return false;
  return true;
}

bool MinimumControlSpace::countsQueries() const {
  for (const auto& in : inputs_)
    if (in->countsQueries()) return true;
  return false;
}

Metric MinimumControlSpace::metricAt(const Vec2& p) const {
  const size_t k = inputs_.size();
  if (k == 1) return inputs_.front()->metricAt(p);
  if (k == 2) return intersect(inputs_[0]->metricAt(p), inputs_[1]->metricAt(p));
  // More inputs: intersection is not associative (the reduction keeps one ellipse inside
  // both, not every one), so an input inside all others is looked for first - it is the
  // one with the largest det Mt - and the fold is the answer otherwise.
  std::array<Metric, 8> local;
  std::vector<Metric> heap;
  Metric* m = local.data();
  if (k > local.size()) {
    heap.resize(k);
    m = heap.data();
  }
  size_t best = 0;
  for (size_t i = 0; i < k; ++i) {
    m[i] = inputs_[i]->metricAt(p);
    if (m[i].transform().determinant() > m[best].transform().determinant()) best = i;
  }
  bool inside = true;
  for (size_t i = 0; i < k && inside; ++i)
    if (i != best) inside = metricInside(m[best], m[i]);
  if (inside) return m[best];
  Metric r = m[0];
  for (size_t i = 1; i < k; ++i) r = intersect(r, m[i]);
  return r;
}

std::shared_ptr<const ControlSpace> minimumOf(const std::shared_ptr<const ControlSpace>& a,
                                              const std::shared_ptr<const ControlSpace>& b) {
  std::vector<std::shared_ptr<const ControlSpace>> inputs;
  for (const auto* s : {&a, &b}) {
    if (const auto* m = dynamic_cast<const MinimumControlSpace*>(s->get()))
      inputs.insert(inputs.end(), m->inputs().begin(), m->inputs().end());
    else
      inputs.push_back(*s);
  }
  return std::make_shared<MinimumControlSpace>(std::move(inputs));
}

}  // namespace anisomesh

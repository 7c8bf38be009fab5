#pragma once
// The minimum (intersection) of several control spaces, evaluated lazily (section 2.4
// without a structure): every query asks each input and intersects the answers, so the
// result is exact at every point - unlike intersectControlSpace(), which stores the
// minimum in the nodes of an interpolated structure and is exact only at its nodes.
#include <memory>
#include <vector>

#include "anisomesh/controlspace/control_space.h"

namespace anisomesh {

class MinimumControlSpace : public ControlSpace {
 public:
  // Holds the inputs (at least one, none null). Throws InvalidArgument for an empty list
  // or a null input, InvalidDomain when their rectangles do not overlap.
  explicit MinimumControlSpace(std::vector<std::shared_ptr<const ControlSpace>> inputs);

  // min(M_1(p), ..., M_k(p)): the unit ball lies inside every input's (within rounding);
  // an input smaller than every other in every direction is returned exactly.
  Metric metricAt(const Vec2& p) const override;
  // Mp of the first input: all inputs describe the same patch's parameter domain.
  Mat2 parameterizationAt(const Vec2& p) const override { return inputs_.front()->parameterizationAt(p); }
  // The common rectangle of the inputs (their intersection).
  Box2 bounds() const override { return bounds_; }
  // When every input's queries are.
  bool concurrentQueries() const override;
  bool countsQueries() const override;
  // The inputs, in the order given.
  const std::vector<std::shared_ptr<const ControlSpace>>& inputs() const { return inputs_; }

 private:
  std::vector<std::shared_ptr<const ControlSpace>> inputs_;
  Box2 bounds_;
};

// The minimum of a and b, where a minimum among them gives its inputs instead of itself:
// folding k spaces pairwise (as the npm package's minimumControlSpace(...spaces) does) builds
// one MinimumControlSpace of all k, so the answer is the k-input one (intersection is not
// associative).
std::shared_ptr<const ControlSpace> minimumOf(const std::shared_ptr<const ControlSpace>& a,
                                              const std::shared_ptr<const ControlSpace>& b);

}  // namespace anisomesh

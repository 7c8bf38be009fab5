// Minimum of two control spaces (section 2.4: intersection of the metrics at the nodes of
// the first, refined where the second is finer).
#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"
#include "bucket_grid.h"

namespace anisomesh {

using controlspace_internal::BucketGrid;
using controlspace_internal::pieceBox;
using controlspace_internal::pointBox;

void intersectControlSpace(AdaptiveControlSpace& cs1, const ControlSpace& cs2, const std::vector<ControlNode>& cs2Nodes,
                           const MinimumOptions& options) {
  require(options.threshold >= 0.0, ErrorCode::InvalidArgument, "minimum threshold must be >= 0");
  const std::unique_ptr<AdaptiveControlSpace> original = cs1.clone();
  auto phase1 = [&](int first, int last) {
    for (int i = first; i < last; ++i)
      if (cs1.nodeIsFree(i)) {
        const Vec2& p = cs1.nodePosition(i);
        cs1.setNodeMetric(i, intersect(original->metricAt(p), cs2.metricAt(p)));
      }
  };
  // Phase 1.
  phase1(0, cs1.nodeCount());
  cs1.applyConstraints();
  // Phase 2: the nodes of cs2 as discrete sources.
  std::vector<Box2> boxes;
  boxes.reserve(cs2Nodes.size());
  for (const auto& nd : cs2Nodes) boxes.push_back(pointBox(nd.position, 0.0));
  const BucketGrid grid(cs1.bounds(), boxes);
  cs1.refine(
      [&](const ControlElement& e) {
        return grid.any(e.box, [&](int k) {
          const ControlNode& nd = cs2Nodes[k];
          if (e.size <= nd.elementSize || !e.box.contains(nd.position)) return false;
          const Metric m = cs1.metricAt(nd.position);
          const Metric target = intersect(original->metricAt(nd.position), nd.metric);
          return difference(m, target) > options.threshold;
        });
      },
      phase1);
  // Phase 3: phase 1 again.
  phase1(0, cs1.nodeCount());
  cs1.applyConstraints();
  if (!options.conservative) return;
  // Phase 3, conservative: where the interpolation exceeds the exact minimum at sample
  // points of an element (sizes larger by e), the element's free nodes shrink by 1 + e
  // (the largest over their elements), so the result errs on the fine side; a few passes
  // because Mt interpolation is not exactly monotone.
  const std::vector<std::vector<int>> elements = cs1.elementNodes();
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<double> grow(cs1.nodeCount(), 1.0);
    bool any = false;
    for (const std::vector<int>& el : elements) {
      double worst = 1.0;
      auto check = [&](const Vec2& p) {
        const Metric r = cs1.metricAt(p);
        const Metric t = intersect(original->metricAt(p), cs2.metricAt(p));
        // Largest ratio of r's size to t's over all directions: sqrt(lmax(Mt_r^-1 M_t Mt_r^-1)).
        const Mat2 ir = r.transform().inverse();
        const Mat2 q = ir * t.tensor() * ir;
        const double half = 0.5 * (q(0, 0) - q(1, 1)), off = 0.5 * (q(0, 1) + q(1, 0));
        worst =
            std::max(worst, std::sqrt(std::max(0.5 * (q(0, 0) + q(1, 1)) + std::sqrt(half * half + off * off), 0.0)));
      };
      if (el.size() == 4) {  // leaf: a 4 x 4 grid of interior points
        const Vec2 &lo = cs1.nodePosition(el[0]), &hi = cs1.nodePosition(el[2]);
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            check(Vec2(lo.x() + (a + 0.5) / 4 * (hi.x() - lo.x()), lo.y() + (b + 0.5) / 4 * (hi.y() - lo.y())));
      } else {  // triangle: the points of barycentric coordinates in quarters, but vertices
        const Vec2 &A = cs1.nodePosition(el[0]), &B = cs1.nodePosition(el[1]), &C = cs1.nodePosition(el[2]);
        for (int a = 0; a <= 4; ++a)
          for (int b = 0; a + b <= 4; ++b)
            if (a < 4 && b < 4 && a + b > 0) check((a * A + b * B + (4 - a - b) * C) / 4.0);
        check((A + B + C) / 3.0);
      }
      if (worst <= 1.0 + 1e-12) continue;
      any = true;
      for (int v : el) grow[v] = std::max(grow[v], worst);
    }
    if (!any) break;
    for (int i = 0; i < cs1.nodeCount(); ++i)
      if (grow[i] > 1.0 && cs1.nodeIsFree(i)) cs1.setNodeMetric(i, cs1.nodeMetric(i).scaled(1.0 / grow[i]));
    cs1.applyConstraints();
  }
}

void intersectControlSpace(AdaptiveControlSpace& cs1, const AdaptiveControlSpace& cs2, const MinimumOptions& options) {
  intersectControlSpace(cs1, cs2, cs2.controlNodes(), options);
}

}  // namespace anisomesh

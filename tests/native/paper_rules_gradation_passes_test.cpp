// Section 2.5.2: the quadtree's upward-then-downward traversal (smoothGradationUpDown)
// beside the work-set (smoothGradation). Both apply only the pairwise rule, so both only
// shrink sizes; the work-set runs to the fixed point, so the bound of eq. 4 holds on every
// edge of the structure, which one up/down pair does not guarantee. The figures printed
// are the ones docs/paper_rules.md quotes.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/controlspace/quadtree_gradation.h"
#include "anisomesh/core/error.h"

using namespace anisomesh;

namespace {

Box2 passesUnitBox() { return Box2{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}; }

// Steep boundary layer and a small isotropic spot (slopes far above a_max).
Metric sharpPassField(const Vec2& p) {
  const double hn = std::min(0.001 + 1.0 * std::abs(p.y() - 0.5), 0.2);
  const Metric layer = Metric::fromSizes(0.0, 0.2, hn);
  const Metric spot = Metric::isotropic(std::min(0.002 + 3.0 * (p - Vec2(0.25, 0.25)).norm(), 0.2));
  return intersect(layer, spot);
}

std::unique_ptr<QuadtreeControlSpace> sharpTree() {
  QuadtreeOptions o;
  o.maxLevel = 7;
  auto cs = std::make_unique<QuadtreeControlSpace>(passesUnitBox(), o);
  ContinuousInsertionOptions c;
  c.threshold = 0.3;
  c.sampleThreshold = 0.05;
  insertMetricFunction(*cs, sharpPassField, c);
  return cs;
}

struct Excess {
  int edges = 0, violating = 0;
  double worst = 0.0;  // largest (h_j - h_i - a d) / (a d) over the structure's edges
};

Excess boundExcess(const AdaptiveControlSpace& cs, double dr) {
  const double a = 2.0 * (dr - 1.0) / (dr + 1.0);
  Excess e;
  for (const auto& ed : cs.structureEdges()) {
    const Vec2 u = cs.nodePosition(ed[1]) - cs.nodePosition(ed[0]);
    const double hi = cs.nodeMetric(ed[0]).sizeAlong(u), hj = cs.nodeMetric(ed[1]).sizeAlong(u);
    const double over = (std::abs(hj - hi) - a * u.norm()) / (a * u.norm());
    ++e.edges;
    if (over > 1e-6) ++e.violating;
    e.worst = std::max(e.worst, over);
  }
  return e;
}

}  // namespace

TEST(PaperRulesGradationPasses, UpDownOnlyShrinksAndWorkSetReachesTheBound) {
  for (double dr : {1.5, 2.0, 8.0}) {
    const auto field = sharpTree();
    const Excess raw = boundExcess(*field, dr);
    auto workSet = field->clone();
    GradationOptions g;
    g.ratio = dr;
    auto t0 = std::chrono::steady_clock::now();
    const int wsUpdates = smoothGradation(*workSet, g);
    const double wsSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Excess ws = boundExcess(*workSet, dr);
    EXPECT_EQ(ws.violating, 0) << dr;

    for (int passes : {1, 2, 4}) {
      auto tree = std::make_unique<QuadtreeControlSpace>(*field);
      TreeGradationOptions o;
      o.ratio = dr;
      o.passes = passes;
      t0 = std::chrono::steady_clock::now();
      const int updates = smoothGradationUpDown(*tree, o);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      EXPECT_GT(updates, 0);
      // Only shrinks: every free node's sizes are at most what they were.
      for (int i = 0; i < tree->nodeCount(); ++i) {
        if (!tree->nodeIsFree(i)) continue;
        for (double ang : {0.0, 0.785, 1.571, 2.356}) {
          const Vec2 u(std::cos(ang), std::sin(ang));
          ASSERT_LE(tree->nodeMetric(i).sizeAlong(u), field->nodeMetric(i).sizeAlong(u) * (1 + 1e-12));
        }
      }
      const Excess ud = boundExcess(*tree, dr);
      EXPECT_LT(ud.violating, raw.violating) << dr;
      std::cout << "[ figures  ] dr " << dr << ": " << raw.edges << " edges, " << raw.violating
                << " over the bound before; work-set " << ws.violating << " (" << wsUpdates << " updates, "
                << wsSeconds * 1e3 << " ms); up/down x" << passes << " " << ud.violating << " (worst excess "
                << ud.worst << ", " << updates << " updates, " << seconds * 1e3 << " ms)\n";
      // The work-set after up/down: same bound, fewer updates left to do.
      GradationOptions again = g;
      smoothGradation(*tree, again);
      EXPECT_EQ(boundExcess(*tree, dr).violating, 0);
    }
  }
}

TEST(PaperRulesGradationPasses, BadOptionsAreRejected) {
  auto cs = sharpTree();
  TreeGradationOptions o;
  o.ratio = 0.5;
  EXPECT_THROW(smoothGradationUpDown(*cs, o), Error);
  o.ratio = 2.0;
  o.passes = 0;
  EXPECT_THROW(smoothGradationUpDown(*cs, o), Error);
}

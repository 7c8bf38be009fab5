// Balanced quadtree control space: structure, interpolation exactness, adaptation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/error.h"
#include "controlspace_test_util.h"

using namespace anisomesh;

namespace {

using anisomesh::test_util::box;

// A tree refined irregularly around a point (deep leaves next to coarse ones).
QuadtreeControlSpace irregularTree(QuadtreeInterpolation interp) {
  QuadtreeOptions o;
  o.initialLevel = 1;
  o.maxLevel = 10;
  o.interpolation = interp;
  o.initialMetric = Metric::isotropic(1.0);
  QuadtreeControlSpace qt(box(0.0, 0.0, 2.0, 1.0), o);
  const Vec2 focus(0.61, 0.37);
  qt.refine([&](const ControlElement& e) { return e.box.contains(focus) && e.size > 2.0 / 256; }, nullptr);
  return qt;
}

SymMt evalField(int kind, const Vec2& p) {
  const double x = p.x(), y = p.y();
  switch (kind) {
    case 0:
      return {3.0, 0.4, 2.0};
    case 1:  // bilinear entries
      return {3.0 + x - 0.5 * y + 0.3 * x * y, 0.2 + 0.1 * x - 0.05 * x * y, 2.5 + 0.2 * x + y + 0.1 * x * y};
    default:  // complete quadratic entries
      return {4.0 + x + 0.3 * y + 0.5 * x * x - 0.2 * x * y + 0.4 * y * y, 0.1 * x - 0.2 * y + 0.05 * x * x,
              3.0 - 0.5 * x + y + 0.3 * y * y + 0.1 * x * y - 0.1 * x * x};
  }
}

void setField(QuadtreeControlSpace& qt, int kind) {
  for (int i = 0; i < qt.nodeCount(); ++i)
    if (qt.nodeIsFree(i)) qt.setNodeMetric(i, toMetric(evalField(kind, qt.nodePosition(i))));
  qt.applyConstraints();
}

double maxFieldError(const QuadtreeControlSpace& qt, int kind, int samples) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 2.0), uy(0.0, 1.0);
  double err = 0.0;
  for (int k = 0; k < samples; ++k) {
    const Vec2 p(ux(rng), uy(rng));
    const SymMt a = qt.mtAt(p), b = evalField(kind, p);
    err = std::max({err, std::abs(a.a - b.a), std::abs(a.b - b.b), std::abs(a.c - b.c)});
  }
  // Also along the leaf sides around the refined region (hanging nodes live there).
  for (int k = 0; k <= 400; ++k) {
    const Vec2 p(0.5 + 0.25 * k / 400.0, 0.25 + 0.125 * std::sin(k * 0.1) * std::sin(k * 0.1));
    const SymMt a = qt.mtAt(p), b = evalField(kind, p);
    err = std::max({err, std::abs(a.a - b.a), std::abs(a.b - b.b), std::abs(a.c - b.c)});
  }
  return err;
}

using anisomesh::test_util::boundaryLayer;

}  // namespace

TEST(ControlSpaceQuadtree, InvalidBoxIsRejected) {
  EXPECT_THROW(QuadtreeControlSpace(box(1.0, 0.0, 0.0, 1.0)), Error);
  try {
    QuadtreeControlSpace qt(box(0.0, 0.0, 1.0, 0.0));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidDomain);
  }
  try {
    QuadtreeControlSpace qt(box(0.0, std::nan(""), 1.0, 1.0));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidDomain);
  }
  QuadtreeOptions o;
  o.maxLevel = 40;
  try {
    QuadtreeControlSpace qt(box(0.0, 0.0, 1.0, 1.0), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
  }
}

TEST(ControlSpaceQuadtree, RefinementKeepsBalanceAndCreatesHangingNodes) {
  for (auto interp : {QuadtreeInterpolation::Bilinear, QuadtreeInterpolation::Serendipity}) {
    QuadtreeControlSpace qt = irregularTree(interp);
    EXPECT_TRUE(qt.isBalanced());
    EXPECT_GT(qt.elementCount(), 20);
    int hanging = 0;
    for (int i = 0; i < qt.nodeCount(); ++i) hanging += qt.nodeIsFree(i) ? 0 : 1;
    EXPECT_GT(hanging, 0);
    // Every leaf found by point location contains the point.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ux(0.0, 2.0), uy(0.0, 1.0);
    for (int k = 0; k < 2000; ++k) {
      const Vec2 p(ux(rng), uy(rng));
      const int c = qt.locateLeaf(p);
      ASSERT_TRUE(qt.isLeaf(c));
      ASSERT_TRUE(qt.cellBox(c).contains(p));
    }
    qt.splitLeaf(qt.locateLeaf(Vec2(1.9, 0.9)));
    EXPECT_TRUE(qt.isBalanced());
  }
}

TEST(ControlSpaceQuadtree, ReproducesConstantFieldExactly) {
  for (auto interp : {QuadtreeInterpolation::Bilinear, QuadtreeInterpolation::Serendipity}) {
    QuadtreeControlSpace qt = irregularTree(interp);
    setField(qt, 0);
    EXPECT_LT(maxFieldError(qt, 0, 5000), 1e-12);
  }
}

TEST(ControlSpaceQuadtree, BilinearReproducesBilinearFieldExactly) {
  QuadtreeControlSpace qt = irregularTree(QuadtreeInterpolation::Bilinear);
  setField(qt, 1);
  EXPECT_LT(maxFieldError(qt, 1, 5000), 1e-12);
  // Refining further keeps the field (new nodes take the interpolation).
  qt.refine([](const ControlElement& e) { return e.box.contains(Vec2(1.5, 0.5)) && e.size > 0.01; }, nullptr);
  EXPECT_TRUE(qt.isBalanced());
  EXPECT_LT(maxFieldError(qt, 1, 5000), 1e-12);
}

TEST(ControlSpaceQuadtree, SerendipityReproducesQuadraticFieldExactly) {
  QuadtreeControlSpace qt = irregularTree(QuadtreeInterpolation::Serendipity);
  setField(qt, 2);
  EXPECT_LT(maxFieldError(qt, 2, 5000), 1e-12);
  qt.refine([](const ControlElement& e) { return e.box.contains(Vec2(1.5, 0.5)) && e.size > 0.01; }, nullptr);
  EXPECT_TRUE(qt.isBalanced());
  EXPECT_LT(maxFieldError(qt, 2, 5000), 1e-12);
  // The bilinear scheme does not reproduce it (sanity check of the test itself).
  QuadtreeControlSpace bl = irregularTree(QuadtreeInterpolation::Bilinear);
  setField(bl, 2);
  EXPECT_GT(maxFieldError(bl, 2, 5000), 1e-4);
}

TEST(ControlSpaceQuadtree, FieldIsContinuousAcrossLevelJumps) {
  // Arbitrary node values (no polynomial field): hanging nodes must still make the
  // interpolation continuous across every leaf side.
  for (auto interp : {QuadtreeInterpolation::Bilinear, QuadtreeInterpolation::Serendipity}) {
    QuadtreeControlSpace qt = irregularTree(interp);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> a(-1.5, 1.5), h(0.01, 0.2);
    for (int i = 0; i < qt.nodeCount(); ++i)
      if (qt.nodeIsFree(i)) qt.setNodeMetric(i, Metric::fromSizes(a(rng), h(rng), h(rng)));
    qt.applyConstraints();
    double worst = 0.0;
    const double eps = 1e-10;
    for (int c : qt.leaves()) {
      const Box2 b = qt.cellBox(c);
      for (int k = 1; k < 8; ++k) {
        const double t = k / 8.0;
        const Vec2 left(b.lo.x(), b.lo.y() + t * b.size().y()), bottom(b.lo.x() + t * b.size().x(), b.lo.y());
        if (b.lo.x() > 0.0) {
          const SymMt u = qt.mtAt(left - Vec2(eps, 0)), v = qt.mtAt(left + Vec2(eps, 0));
          worst = std::max({worst, std::abs(u.a - v.a), std::abs(u.b - v.b), std::abs(u.c - v.c)});
        }
        if (b.lo.y() > 0.0) {
          const SymMt u = qt.mtAt(bottom - Vec2(0, eps)), v = qt.mtAt(bottom + Vec2(0, eps));
          worst = std::max({worst, std::abs(u.a - v.a), std::abs(u.b - v.b), std::abs(u.c - v.c)});
        }
      }
    }
    EXPECT_LT(worst, 1e-4);  // node values are O(100); a missing constraint jumps by O(10)
  }
}

TEST(ControlSpaceQuadtree, AdaptsToAnisotropicBoundaryLayer) {
  for (auto interp : {QuadtreeInterpolation::Bilinear, QuadtreeInterpolation::Serendipity}) {
    QuadtreeOptions o;
    o.maxLevel = 10;
    o.interpolation = interp;
    QuadtreeControlSpace qt(box(0.0, 0.0, 1.0, 1.0), o);
    ContinuousInsertionOptions c;
    c.threshold = 0.3;
    c.sampleThreshold = 0.05;
    insertMetricFunction(qt, boundaryLayer, c);
    EXPECT_TRUE(qt.isBalanced());
    const double worst = anisomesh::test_util::worstLengthError(qt, boundaryLayer);
    EXPECT_LT(worst, 0.1) << "leaves " << qt.elementCount();
    // Strong anisotropy is captured at the layer.
    EXPECT_GT(qt.metricAt(Vec2(0.3, 0.5)).aspectRatio(), 90.0);
  }
}

TEST(ControlSpaceQuadtree, RefineByDifferenceSplitsWhereNodesDiffer) {
  QuadtreeOptions o;
  o.maxLevel = 9;
  QuadtreeControlSpace qt(box(0.0, 0.0, 1.0, 1.0), o);
  for (int i = 0; i < qt.nodeCount(); ++i)
    qt.setNodeMetric(i, Metric::isotropic(qt.nodePosition(i).x() < 0.3 ? 0.01 : 0.1));
  const int before = qt.elementCount();
  qt.refineByDifference(0.5);
  EXPECT_GT(qt.elementCount(), before);
  EXPECT_TRUE(qt.isBalanced());
}

TEST(ControlSpaceQuadtree, OutsidePointsAreClamped) {
  QuadtreeControlSpace qt = irregularTree(QuadtreeInterpolation::Bilinear);
  setField(qt, 1);
  const SymMt a = qt.mtAt(Vec2(-5.0, 0.5)), b = evalField(1, Vec2(0.0, 0.5));
  EXPECT_NEAR(a.a, b.a, 1e-12);
  const SymMt c = qt.mtAt(Vec2(std::nan(""), std::nan("")));
  EXPECT_TRUE(std::isfinite(c.a));
}

// refineNear (a dragged source's refinement) offers only the leaves near its boxes, and
// splits exactly as refine with the same predicate: the same cells, nodes and values.
TEST(ControlSpaceQuadtree, RefineNearSplitsAsRefine) {
  for (auto interp : {QuadtreeInterpolation::Bilinear, QuadtreeInterpolation::Serendipity}) {
    const std::vector<Box2> near{Box2{Vec2(0.3, 0.2), Vec2(0.5, 0.45)}, Box2{Vec2(1.6, 0.7), Vec2(1.6, 0.7)}};
    int offered = 0;
    const ElementPredicate pred = [&](const ControlElement& e) {
      ++offered;
      bool meets = false;
      for (const Box2& r : near)
        meets = meets || !(r.hi.x() < e.box.lo.x() || r.lo.x() > e.box.hi.x() || r.hi.y() < e.box.lo.y() ||
                           r.lo.y() > e.box.hi.y());
      return meets && e.size > 0.02;
    };
    QuadtreeControlSpace a = irregularTree(interp), b = irregularTree(interp);
    a.refine(pred, nullptr);
    const int all = offered;
    offered = 0;
    b.refineNear(near, pred, nullptr);
    EXPECT_LT(offered, all);
    ASSERT_EQ(a.nodeCount(), b.nodeCount());
    ASSERT_EQ(a.leaves(), b.leaves());
    for (int i = 0; i < a.nodeCount(); ++i) {
      ASSERT_EQ(a.nodePosition(i), b.nodePosition(i));
      ASSERT_EQ(a.nodeMt(i).a, b.nodeMt(i).a);
      ASSERT_EQ(a.nodeMt(i).b, b.nodeMt(i).b);
      ASSERT_EQ(a.nodeMt(i).c, b.nodeMt(i).c);
    }
  }
}

TEST(ControlSpaceQuadtree, ApplyConstraintsTouchedMatchesThePassInOrder) {
  // applyConstraintsTouched() visits only the constraints reading a flagged node: the same
  // rewrites, in the same order, as a pass over every constraint that rewrites those whose
  // node or a master is flagged (flagging what it rewrites), and the same bits as
  // applyConstraints() after the changes.
  for (auto interp : {QuadtreeInterpolation::Bilinear, QuadtreeInterpolation::Serendipity}) {
    for (int trial = 0; trial < 6; ++trial) {
      QuadtreeControlSpace qt = irregularTree(interp);
      std::mt19937 rng(40 + trial);
      std::uniform_real_distribution<double> a(-1.5, 1.5), h(0.01, 0.2), u(0.0, 1.0);
      for (int i = 0; i < qt.nodeCount(); ++i)
        if (qt.nodeIsFree(i)) qt.setNodeMetric(i, Metric::fromSizes(a(rng), h(rng), h(rng)));
      qt.applyConstraints();
      // Change a few nodes (free and hanging), few enough that most constraints are untouched.
      std::vector<char> touched(qt.nodeCount(), 0);
      std::vector<int> touchedList;
      const double share = trial < 3 ? 0.03 : 0.15;
      for (int i = 0; i < qt.nodeCount(); ++i)
        if (u(rng) < share || (touchedList.empty() && i + 1 == qt.nodeCount())) {
          qt.setNodeMetric(i, Metric::fromSizes(a(rng), h(rng), h(rng)));
          touched[i] = 1;
          touchedList.push_back(i);
        }
      ASSERT_FALSE(touchedList.empty());
      // The reference pass, on a copy.
      std::unique_ptr<AdaptiveControlSpace> ref = qt.clone();
      std::vector<char> refTouched = touched;
      std::vector<int> expected;
      for (const auto& hn : ref->hangingNodes()) {
        if (!refTouched[hn.node] && !refTouched[hn.masters[0]] && !refTouched[hn.masters[1]] &&
            !refTouched[hn.masters[2]])
          continue;
        SymMt r{0.0, 0.0, 0.0};
        for (int j = 0; j < 3; ++j) {
          const SymMt& m = ref->nodeMt(hn.masters[j]);
          r.a += hn.weights[j] * m.a;
          r.b += hn.weights[j] * m.b;
          r.c += hn.weights[j] * m.c;
        }
        ref->setNodeMetric(hn.node, toMetric(r));
        refTouched[hn.node] = 1;
        expected.push_back(hn.node);
      }
      std::unique_ptr<AdaptiveControlSpace> all = qt.clone();
      all->applyConstraints();
      std::vector<AdaptiveControlSpace::RewrittenNode> rewritten;
      qt.applyConstraintsTouched(touched, touchedList, rewritten);
      std::vector<int> got;
      for (const auto& w : rewritten) got.push_back(w.node);
      EXPECT_EQ(got, expected);
      EXPECT_LT(expected.size(), ref->hangingNodes().size());
      int differing = 0;
      for (int i = 0; i < qt.nodeCount(); ++i) {
        const SymMt &x = qt.nodeMt(i), &y = all->nodeMt(i);
        differing += !(x.a == y.a && x.b == y.b && x.c == y.c);
      }
      EXPECT_EQ(differing, 0);
      EXPECT_EQ(touched, refTouched);
    }
  }
}

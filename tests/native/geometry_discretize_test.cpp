#include <gtest/gtest.h>

#include <cmath>

#include "anisomesh/boundary/discretize.h"
#include "anisomesh/core/error.h"

#include "geometry_test_util.h"

using namespace anisomesh;

namespace {

Box2 bigBox() { return Box2{Vec2(-100, -100), Vec2(100, 100)}; }

AnalyticControlSpace gradedInX() {
  return AnalyticControlSpace(bigBox(), [](const Vec2& p) { return Metric::isotropic(0.05 + 0.1 * std::abs(p.x())); });
}

using anisomesh::test_util::rectangle;

}  // namespace

TEST(GeometryDiscretize, MetricLengthOfSegmentUnderGradedMetric) {
  const LineCurve l({0, 0}, {3, 0});
  const auto cs = gradedInX();
  // Exact: integral of 1 / (0.05 + 0.1 x) over [0, 3] = 10 ln(0.35 / 0.05).
  EXPECT_NEAR(metricLength(l, cs), 10.0 * std::log(7.0), 1e-7);
}

TEST(GeometryDiscretize, SegmentsHaveUnitMetricLength) {
  const LineCurve l({0, 0}, {3, 0});
  const auto cs = gradedInX();
  const std::vector<double> ts = discretizeCurve(l, cs);
  const double total = metricLength(l, cs);
  ASSERT_EQ(int(ts.size()) - 1, int(std::round(total)));
  EXPECT_EQ(ts.front(), 0.0);
  EXPECT_EQ(ts.back(), 1.0);
  for (size_t i = 0; i + 1 < ts.size(); ++i) {
    const double m = metricLength(l, cs, ts[i], ts[i + 1]);
    EXPECT_GE(m, 0.9) << i;
    EXPECT_LE(m, 1.1) << i;
    // Equal fractions: every segment has the same metric length.
    EXPECT_NEAR(m, total / (ts.size() - 1), 1e-6);
  }
  // The physical spacing grows with the size.
  EXPECT_LT(ts[1] - ts[0], ts.back() - ts[ts.size() - 2]);
}

// A metric with kinks (as a control space's interpolation has at its cell edges): the
// absolute tolerance stops the bisection from chasing each kink down to 1e-8 metric units,
// and the segments stay equal in metric length to 1e-5 (measured with a tight quadrature).
TEST(GeometryDiscretize, KinkedMetricSegmentsStayEqualWithFewerQueries) {
  const LineCurve l({0, 0}, {3, 0});
  long queries = 0;
  const AnalyticControlSpace cs(bigBox(), [&queries](const Vec2& p) {
    ++queries;
    // Sizes linear between "nodes" 0.05 apart, alternately 0.02 and 0.04: a kink at each.
    const double s = p.x() / 0.05;
    return Metric::isotropic(0.02 + 0.04 * std::abs(s - 2.0 * std::floor(0.5 * s + 0.5)));
  });
  DiscretizeOptions tight;
  tight.absoluteTolerance = 0.0;
  const std::vector<double> exact = discretizeCurve(l, cs, 1, tight);
  const long tightQueries = queries;
  queries = 0;
  const std::vector<double> ts = discretizeCurve(l, cs);
  const long defaultQueries = queries;
  // Measured: 13,608 -> 9,860 queries (on p2's boundary: 53,822 -> 30,016 per run).
  EXPECT_LT(defaultQueries, 0.8 * tightQueries) << tightQueries;
  ASSERT_EQ(ts.size(), exact.size());
  const double total = metricLength(l, cs, 0.0, 1.0, 1e-12);
  const double each = total / double(ts.size() - 1);
  double worst = 0.0;
  for (size_t i = 0; i + 1 < ts.size(); ++i)
    worst = std::max(worst, std::abs(metricLength(l, cs, ts[i], ts[i + 1], 1e-12) / each - 1.0));
  // Measured: 2.5e-6 (with absoluteTolerance 1e-2 even the segment count changes).
  EXPECT_LT(worst, 1e-5);
}

TEST(GeometryDiscretize, AnisotropicMetricFollowsDirection) {
  // 0.1 along x, 0.5 along y.
  const AnalyticControlSpace cs(bigBox(), [](const Vec2&) { return Metric::fromSizes(0.0, 0.1, 0.5); });
  EXPECT_EQ(discretizeCurve(LineCurve({0, 0}, {1, 0}), cs).size(), 11u);
  EXPECT_EQ(discretizeCurve(LineCurve({0, 0}, {0, 1}), cs).size(), 3u);
}

TEST(GeometryDiscretize, ArcPointsLieOnCircleEvenlySpaced) {
  const ArcCurve arc({1, 2}, 1.5, 0.3, 2.5);
  const UniformControlSpace cs(bigBox(), Metric::isotropic(0.1));
  const std::vector<double> ts = discretizeCurve(arc, cs);
  EXPECT_EQ(int(ts.size()) - 1, int(std::round(arc.length() / 0.1)));
  for (size_t i = 0; i < ts.size(); ++i) {
    EXPECT_NEAR((arc.point(ts[i]) - Vec2(1, 2)).norm(), 1.5, 1e-12);
    if (i > 0) {
      EXPECT_NEAR(ts[i] - ts[i - 1], 1.0 / (ts.size() - 1), 1e-9);
    }
  }
}

TEST(GeometryDiscretize, ShortAndClosedCurvesGetMinimumSegments) {
  const UniformControlSpace coarse(bigBox(), Metric::isotropic(100.0));
  EXPECT_EQ(discretizeCurve(LineCurve({0, 0}, {1, 0}), coarse).size(), 2u);
  Domain d;
  d.outer.add(std::make_shared<ArcCurve>(ArcCurve::circle({0, 0}, 1.0, 3)));
  const auto loops = discretizeDomain(d, coarse);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].points.size(), 3u);
  EXPECT_EQ(loops[0].edgeRefs, std::vector<int>({3, 3, 3}));
}

TEST(GeometryDiscretize, PolylineCornersAreKept) {
  const PolylineCurve p({{0, 0}, {1, 0}, {1, 0.35}});
  const UniformControlSpace cs(bigBox(), Metric::isotropic(0.1));
  const auto ts = discretizeCurve(p, cs);
  bool corner = false;
  for (double t : ts) corner = corner || (p.point(t) - Vec2(1, 0)).norm() < 1e-12;
  EXPECT_TRUE(corner);
  EXPECT_EQ(ts.size(), 10u + 4u);  // 10 + round(3.5) = 14 segments
}

TEST(GeometryDiscretize, DomainLoopsOrientationAndRefs) {
  Domain d;
  d.outer = rectangle(0, 0, 2, 1);
  // A clockwise-written hole comes out clockwise, a counter-clockwise one is reversed.
  Contour hole;
  hole.add(std::make_shared<ArcCurve>(ArcCurve::circle({1, 0.5}, 0.2, 9)));
  d.holes.push_back(hole);
  const UniformControlSpace cs(bigBox(), Metric::isotropic(0.1));
  const auto loops = discretizeDomain(d, cs);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_GT(signedArea(loops[0].points), 0);
  EXPECT_LT(signedArea(loops[1].points), 0);
  EXPECT_EQ(loops[0].points.size(), 60u);
  EXPECT_EQ(loops[0].edgeRefs.size(), loops[0].points.size());
  // Edge i joins points i and i+1: the bottom edge (ref 1) is horizontal at y = 0.
  for (size_t i = 0; i < loops[0].points.size(); ++i) {
    const Vec2 a = loops[0].points[i], b = loops[0].points[(i + 1) % loops[0].points.size()];
    if (loops[0].edgeRefs[i] == 1) {
      EXPECT_NEAR(a.y(), 0, 1e-14);
      EXPECT_NEAR(b.y(), 0, 1e-14);
    }
  }
  for (size_t i = 0; i < loops[1].points.size(); ++i) {
    EXPECT_EQ(loops[1].edgeRefs[i], 9);
    EXPECT_NEAR((loops[1].points[i] - Vec2(1, 0.5)).norm(), 0.2, 1e-12);
  }
}

TEST(GeometryDiscretize, SharedCurveIsDiscretizedOnce) {
  // Two faces sharing the segment x = 1, each using it in its own direction.
  const auto shared = std::make_shared<LineCurve>(Vec2(1, 0), Vec2(1, 1), 7);
  Domain left, right;
  left.outer.add(std::make_shared<LineCurve>(Vec2(0, 0), Vec2(1, 0)));
  left.outer.add(shared);
  left.outer.add(std::make_shared<PolylineCurve>(std::vector<Vec2>{{1, 1}, {0, 1}, {0, 0}}));
  right.outer.add(std::make_shared<PolylineCurve>(std::vector<Vec2>{{1, 0}, {2, 0}, {2, 1}, {1, 1}}));
  right.outer.add(shared, /*reversed=*/true);
  const AnalyticControlSpace cs(bigBox(), [](const Vec2& p) { return Metric::isotropic(0.02 + 0.1 * p.y()); });
  const auto faces = discretizeDomains({&left, &right}, cs);
  auto onShared = [](const BoundaryLoop& l) {
    std::vector<Vec2> pts;
    for (const Vec2& p : l.points)
      if (std::abs(p.x() - 1) < 1e-14 && p.y() > 1e-14 && p.y() < 1 - 1e-14) pts.push_back(p);
    std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) { return a.y() < b.y(); });
    return pts;
  };
  const auto a = onShared(faces[0][0]), b = onShared(faces[1][0]);
  ASSERT_GT(a.size(), 5u);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);  // bit-identical
}

TEST(GeometryDiscretize, BudgetExceeded) {
  const UniformControlSpace tiny(bigBox(), Metric::isotropic(1e-9));
  DiscretizeOptions o;
  o.maxSegments = 1000;
  try {
    discretizeCurve(LineCurve({0, 0}, {1, 0}), tiny, 1, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ElementBudgetExceeded);
    EXPECT_NE(std::string(e.what()).find("1000"), std::string::npos);
  }
}

TEST(GeometryDiscretize, CurvedSegmentsUnderAnisotropicVaryingMetric) {
  // Every segment of a long enough curve has metric length L / n in [0.9, 1.1].
  const AnalyticControlSpace cs(bigBox(), [](const Vec2& p) {
    return Metric::fromSizes(0.3 + 0.2 * p.x(), 0.02 + 0.01 * std::abs(p.y()), 0.15);
  });
  const std::vector<std::shared_ptr<Curve>> curves{
      std::make_shared<BezierCurve>(Vec2(0, 0), Vec2(1, 2), Vec2(2, -1), Vec2(3, 1)),
      std::make_shared<BSplineCurve>(std::vector<Vec2>{{0, 0}, {1, 1}, {2, -1}, {3, 1}, {4, 0}}),
      std::make_shared<ArcCurve>(Vec2(1, 1), 1.0, -1.0, 2.5)};
  for (const auto& c : curves) {
    SCOPED_TRACE(c->typeName());
    const auto ts = discretizeCurve(*c, cs);
    ASSERT_GT(ts.size(), 6u);
    for (size_t i = 0; i + 1 < ts.size(); ++i) {
      const double m = metricLength(*c, cs, ts[i], ts[i + 1]);
      EXPECT_GE(m, 0.9);
      EXPECT_LE(m, 1.1);
    }
  }
}

namespace {

// A half disc whose arc passes just above a small hole: with a coarse metric the arc's
// chords cut through the hole although the curves do not touch.
Domain halfDiscWithHoleNearArc() {
  Domain d;
  d.outer.add(std::make_shared<ArcCurve>(Vec2(0, 0), 1.0, 0.0, M_PI, 1));
  d.outer.add(std::make_shared<LineCurve>(Vec2(-1, 0), Vec2(1, 0), 2));
  Contour hole;
  hole.add(std::make_shared<ArcCurve>(ArcCurve::circle({0, 0.9}, 0.05, 3)));
  d.holes.push_back(hole);
  return d;
}

std::vector<std::vector<Vec2>> polygonsOf(const std::vector<BoundaryLoop>& loops) {
  std::vector<std::vector<Vec2>> p;
  for (const auto& l : loops) p.push_back(l.points);
  return p;
}

}  // namespace

TEST(GeometryDiscretize, CrossingChordsAreRefined) {
  const Domain d = halfDiscWithHoleNearArc();
  ASSERT_NO_THROW(validateDomain(d));
  const UniformControlSpace coarse(bigBox(), Metric::isotropic(1.0));
  PolygonCrossing x;
  DiscretizeOptions off;
  off.refineCrossings = false;
  EXPECT_TRUE(findPolygonCrossing(polygonsOf(discretizeDomain(d, coarse, off)), &x));
  const auto loops = discretizeDomain(d, coarse);
  EXPECT_FALSE(findPolygonCrossing(polygonsOf(loops), &x));
  EXPECT_GT(loops[0].points.size(), 5u);
  DiscretizeOptions none;
  none.maxRefinementRounds = 0;
  try {
    discretizeDomain(d, coarse, none);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::SelfIntersectingContour);
    EXPECT_NE(std::string(e.what()).find("the boundary discretization crosses itself near"), std::string::npos);
  }
}

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/curve.h"

using namespace anisomesh;

namespace {

// Central differences of point() and derivative() must match the analytic derivatives.
void expectConsistentDerivatives(const Curve& c, double tol = 1e-5) {
  const double h = 1e-6;
  for (double t : {0.1, 0.27, 0.5, 0.73, 0.9}) {
    const Vec2 d = (c.point(t + h) - c.point(t - h)) / (2 * h);
    EXPECT_LT((d - c.derivative(t)).norm(), tol * (1 + d.norm())) << c.typeName() << " t=" << t;
    const Vec2 dd = (c.derivative(t + h) - c.derivative(t - h)) / (2 * h);
    EXPECT_LT((dd - c.secondDerivative(t)).norm(), 1e-3 * (1 + dd.norm())) << c.typeName() << " t=" << t;
  }
}

}  // namespace

TEST(GeometryCurve, LinePointDerivativeLength) {
  const LineCurve l({1, 2}, {4, 6}, 7);
  EXPECT_EQ(l.ref(), 7);
  EXPECT_LT((l.point(0.5) - Vec2(2.5, 4)).norm(), 1e-15);
  EXPECT_LT((l.derivative(0.3) - Vec2(3, 4)).norm(), 1e-15);
  EXPECT_EQ(l.secondDerivative(0.3), Vec2::Zero());
  EXPECT_DOUBLE_EQ(l.length(), 5.0);
  EXPECT_NEAR(curveLength(l), 5.0, 1e-12);
}

TEST(GeometryCurve, ArcFromAnglesLiesOnCircle) {
  const ArcCurve a({1, -1}, 2.0, 0.25, 2.0);
  for (double t = 0; t <= 1.0; t += 0.125) EXPECT_NEAR((a.point(t) - Vec2(1, -1)).norm(), 2.0, 1e-14);
  EXPECT_NEAR(a.length(), 2.0 * 1.75, 1e-14);
  EXPECT_NEAR(curveLength(a), a.length(), 1e-9);
  expectConsistentDerivatives(a);
}

TEST(GeometryCurve, ArcThroughThreePointsBothOrientations) {
  // Counter-clockwise quarter circle through (1,0), (cos45, sin45), (0,1).
  const double s = std::sqrt(0.5);
  const ArcCurve ccw = ArcCurve::throughPoints({1, 0}, {s, s}, {0, 1});
  EXPECT_LT(ccw.center().norm(), 1e-12);
  EXPECT_NEAR(ccw.radius(), 1.0, 1e-12);
  EXPECT_NEAR(ccw.length(), M_PI / 2, 1e-12);
  EXPECT_LT((ccw.end() - Vec2(0, 1)).norm(), 1e-12);
  EXPECT_LT((ccw.point(0.5) - Vec2(s, s)).norm(), 1e-12);
  // Clockwise three-quarter arc from (1,0) through (0,-1) to (0,1).
  const ArcCurve cw = ArcCurve::throughPoints({1, 0}, {0, -1}, {0, 1});
  EXPECT_NEAR(cw.length(), 1.5 * M_PI, 1e-12);
  EXPECT_LT((cw.point(1.0 / 3.0) - Vec2(0, -1)).norm(), 1e-12);
}

TEST(GeometryCurve, ArcErrors) {
  try {
    ArcCurve::throughPoints({0, 0}, {1, 1}, {2, 2});
    FAIL() << "collinear points accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
    EXPECT_NE(std::string(e.what()).find("collinear"), std::string::npos);
  }
  EXPECT_THROW(ArcCurve({0, 0}, -1.0, 0, 1), Error);
  EXPECT_THROW(ArcCurve({0, 0}, 1.0, 0, NAN), Error);
}

TEST(GeometryCurve, CircleIsClosed) {
  const ArcCurve c = ArcCurve::circle({3, 4}, 0.5, 2);
  EXPECT_LT((c.start() - c.end()).norm(), 1e-12);
  EXPECT_NEAR(c.length(), M_PI, 1e-14);
}

TEST(GeometryCurve, PolylineArcLengthParameterAndBreakpoints) {
  const PolylineCurve p({{0, 0}, {3, 0}, {3, 1}});
  EXPECT_DOUBLE_EQ(p.length(), 4.0);
  EXPECT_LT((p.point(0.5) - Vec2(2, 0)).norm(), 1e-14);
  EXPECT_LT((p.point(0.875) - Vec2(3, 0.5)).norm(), 1e-14);
  ASSERT_EQ(p.breakpoints().size(), 1u);
  EXPECT_DOUBLE_EQ(p.breakpoints()[0], 0.75);
  EXPECT_LT((p.derivative(0.9) - Vec2(0, 4)).norm(), 1e-12);  // |c'| = total length
  EXPECT_TRUE(PolylineCurve({{0, 0}, {1, 0}, {1, 1}}, 0, false).breakpoints().empty());
  EXPECT_THROW(PolylineCurve({{0, 0}}), Error);
}

TEST(GeometryCurve, BezierEndpointsTangentsAndLength) {
  const BezierCurve b({0, 0}, {1, 2}, {3, 2}, {4, 0});
  EXPECT_LT((b.start() - Vec2(0, 0)).norm(), 1e-15);
  EXPECT_LT((b.end() - Vec2(4, 0)).norm(), 1e-15);
  EXPECT_LT((b.derivative(0) - Vec2(3, 6)).norm(), 1e-14);
  EXPECT_LT((b.derivative(1) - Vec2(3, -6)).norm(), 1e-14);
  expectConsistentDerivatives(b);
  // A straight Bezier with evenly spaced control points has its chord length.
  EXPECT_NEAR(BezierCurve({0, 0}, {1, 0}, {2, 0}, {3, 0}).length(), 3.0, 1e-12);
}

TEST(GeometryCurve, BSplineClampedInterpolatesEndsAndMatchesBezier) {
  // With exactly 4 control points a clamped cubic B-spline is the Bezier curve.
  const BSplineCurve s({{0, 0}, {1, 2}, {3, 2}, {4, 0}});
  const BezierCurve b({0, 0}, {1, 2}, {3, 2}, {4, 0});
  for (double t = 0; t <= 1.0; t += 0.1) {
    EXPECT_LT((s.point(t) - b.point(t)).norm(), 1e-12);
    EXPECT_LT((s.derivative(t) - b.derivative(t)).norm(), 1e-11);
    EXPECT_LT((s.secondDerivative(t) - b.secondDerivative(t)).norm(), 1e-10);
  }
  const BSplineCurve longer({{0, 0}, {1, 1}, {2, -1}, {3, 1}, {4, -1}, {5, 0}});
  EXPECT_LT((longer.start() - Vec2(0, 0)).norm(), 1e-14);
  EXPECT_LT((longer.end() - Vec2(5, 0)).norm(), 1e-14);
  expectConsistentDerivatives(longer);
  EXPECT_GT(longer.length(), 5.0);
  EXPECT_THROW(BSplineCurve({{0, 0}, {1, 0}, {2, 0}}), Error);
}

// pointAndDerivative(t) gives the bits of point(t) and derivative(t) (an arc shares one
// sine/cosine pair; other curves call both): discretization may use either.
TEST(GeometryCurve, PointAndDerivativeAreThoseOfPointAndDerivative) {
  const ArcCurve arcs[] = {ArcCurve(Vec2(0.3, -1.2), 0.7, -2.0, 9.5), ArcCurve::circle(Vec2(1e3, 2.0), 1e-3),
                           ArcCurve(Vec2(0, 0), 5.0, 3.0, -40.0)};
  const LineCurve line(Vec2(0.1, 0.2), Vec2(-3.0, 4.0));
  std::vector<const Curve*> curves{&line};
  for (const ArcCurve& a : arcs) curves.push_back(&a);
  for (const Curve* c : curves)
    for (int k = 0; k <= 1000; ++k) {
      const double t = k / 1000.0 + (k % 7) * 1e-9;
      Vec2 p, d;
      c->pointAndDerivative(t, p, d);
      const Vec2 p0 = c->point(t), d0 = c->derivative(t);
      ASSERT_TRUE(p.x() == p0.x() && p.y() == p0.y() && d.x() == d0.x() && d.y() == d0.y())
          << c->typeName() << " at t = " << t;
    }
}

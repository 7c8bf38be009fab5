#include <gtest/gtest.h>

#include <cmath>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/domain.h"

#include "geometry_test_util.h"

using namespace anisomesh;

namespace {

using anisomesh::test_util::rectangle;

Contour circle(double x, double y, double r) {
  Contour c;
  c.add(std::make_shared<ArcCurve>(ArcCurve::circle({x, y}, r, 5)));
  return c;
}

// Runs validateDomain and checks the error code and a message fragment.
void expectInvalid(const Domain& d, ErrorCode code, const std::string& fragment) {
  try {
    validateDomain(d);
    FAIL() << "domain accepted, expected " << errorCodeName(code);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(GeometryDomain, ValidRectangleWithHoles) {
  Domain d;
  d.outer = rectangle(0, 0, 10, 5);
  d.holes = {circle(2.5, 2.5, 1), circle(5.5, 2, 0.5), circle(8, 3, 0.25)};
  EXPECT_NO_THROW(validateDomain(d));
  const Box2 b = domainBounds(d);
  EXPECT_NEAR(b.lo.x(), 0, 1e-12);
  EXPECT_NEAR(b.hi.y(), 5, 1e-12);
}

TEST(GeometryDomain, MixedCurvesAndReversedUse) {
  Domain d;
  d.outer.add(std::make_shared<LineCurve>(Vec2(0, 0), Vec2(2, 0)));
  d.outer.add(std::make_shared<BezierCurve>(Vec2(2, 0), Vec2(3, 1), Vec2(1, 2), Vec2(2, 3)));
  d.outer.add(std::make_shared<LineCurve>(Vec2(0, 3), Vec2(2, 3)), /*reversed=*/true);
  d.outer.add(std::make_shared<PolylineCurve>(std::vector<Vec2>{{0, 3}, {-0.5, 1.5}, {0, 0}}));
  EXPECT_NO_THROW(validateDomain(d));
  EXPECT_GT(signedArea(sampleContour(d.outer)), 0.0);
}

TEST(GeometryDomain, OpenContourNamesCurveAndGap) {
  Domain d;
  d.outer = rectangle(0, 0, 1, 1);
  d.outer.curves[2].curve = std::make_shared<LineCurve>(Vec2(1, 1), Vec2(0.1, 1));
  expectInvalid(d, ErrorCode::OpenContour, "outer, curve 2 (line) ends at (0.1, 1)");
}

TEST(GeometryDomain, OpenHoleIsNamed) {
  Domain d;
  d.outer = rectangle(0, 0, 10, 10);
  Contour h;
  h.add(std::make_shared<ArcCurve>(Vec2(5, 5), 1.0, 0.0, 3.0));
  d.holes.push_back(h);
  expectInvalid(d, ErrorCode::OpenContour, "holes[0], curve 0 (arc)");
}

TEST(GeometryDomain, EmptyContourIsOpen) {
  Domain d;
  expectInvalid(d, ErrorCode::OpenContour, "outer: contour has no curves");
}

TEST(GeometryDomain, ZeroLengthCurve) {
  Domain d;
  d.outer = rectangle(0, 0, 1, 1);
  d.outer.curves.insert(d.outer.curves.begin() + 1, {std::make_shared<LineCurve>(Vec2(1, 0), Vec2(1, 0)), false});
  expectInvalid(d, ErrorCode::ZeroLengthCurve, "outer, curve 1 (line): zero length at (1, 0)");
}

TEST(GeometryDomain, SelfIntersectingBowTie) {
  Domain d;
  d.outer.add(std::make_shared<LineCurve>(Vec2(0, 0), Vec2(1, 1)));
  d.outer.add(std::make_shared<LineCurve>(Vec2(1, 1), Vec2(1, 0)));
  d.outer.add(std::make_shared<LineCurve>(Vec2(1, 0), Vec2(0, 1)));
  d.outer.add(std::make_shared<LineCurve>(Vec2(0, 1), Vec2(0, 0)));
  expectInvalid(d, ErrorCode::SelfIntersectingContour, "near (0.5, 0.5)");
}

TEST(GeometryDomain, SelfIntersectingCurvedContour) {
  // A Bezier loop that crosses itself.
  Domain d;
  d.outer.add(std::make_shared<BezierCurve>(Vec2(0, 0), Vec2(3, 3), Vec2(-3, 3), Vec2(1, 0)));
  d.outer.add(std::make_shared<LineCurve>(Vec2(1, 0), Vec2(0, 0)));
  expectInvalid(d, ErrorCode::SelfIntersectingContour, "the contour intersects itself");
}

// Short segments 1e-6 apart do not touch: the tolerance is a distance (1e-12 of the
// polygons' extent), not a cross product that grows as 1 / length (with which segments
// shorter than 2e-6 "touched" a polygon 1e-6 away, and refining them made it worse).
TEST(GeometryDomain, FineSegmentsCloseToEachOtherDoNotMeet) {
  std::vector<Vec2> outer{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<Vec2> hole;
  // A hole whose bottom runs 1e-6 above the outer bottom side, both cut into 1e-7 pieces there.
  for (int i = 0; i <= 1000; ++i) hole.push_back({0.45 + 1e-4 * i, 1e-6});
  hole.push_back({0.55, 0.5});
  hole.push_back({0.45, 0.5});
  std::vector<Vec2> fine{{0, 0}};
  for (int i = 0; i <= 1000; ++i) fine.push_back({0.45 + 1e-7 * i, 0.0});
  fine.insert(fine.end(), {{1, 0}, {1, 1}, {0, 1}});
  std::reverse(hole.begin(), hole.end());
  PolygonCrossing x;
  EXPECT_FALSE(findPolygonCrossing({fine, hole}, &x)) << x.where.transpose();
  EXPECT_FALSE(findPolygonCrossing({outer, hole}, &x)) << x.where.transpose();
  // Moved onto the side, the hole touches it.
  for (Vec2& p : hole)
    if (p.y() == 1e-6) p.y() = 0.0;
  EXPECT_TRUE(findPolygonCrossing({fine, hole}, &x));
}

TEST(GeometryDomain, HoleCrossingOuterContour) {
  Domain d;
  d.outer = rectangle(0, 0, 4, 4);
  d.holes = {circle(4, 2, 1)};
  expectInvalid(d, ErrorCode::SelfIntersectingContour, "holes[0], curve 0 (arc)");
}

TEST(GeometryDomain, HolesCrossingEachOther) {
  Domain d;
  d.outer = rectangle(0, 0, 10, 10);
  d.holes = {circle(4, 5, 1), circle(5, 5, 1)};
  expectInvalid(d, ErrorCode::SelfIntersectingContour, "the contours cross or touch");
}

TEST(GeometryDomain, HoleOutsideOuter) {
  Domain d;
  d.outer = rectangle(0, 0, 4, 4);
  d.holes = {circle(2, 2, 0.5), circle(10, 10, 1)};
  expectInvalid(d, ErrorCode::HoleOutsideDomain, "holes[1] is not inside the outer contour");
}

TEST(GeometryDomain, NestedHolesOverlap) {
  Domain d;
  d.outer = rectangle(0, 0, 10, 10);
  d.holes = {circle(5, 5, 3), circle(5, 5, 1)};
  expectInvalid(d, ErrorCode::HoleOutsideDomain, "holes[1] lies inside holes[0]");
}

TEST(GeometryDomain, ManyHolesValidateQuickly) {
  // 400 small holes: the grid keeps the crossing test near linear.
  Domain d;
  d.outer = rectangle(0, 0, 20, 20);
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) d.holes.push_back(circle(0.5 + i, 0.5 + j, 0.3));
  EXPECT_NO_THROW(validateDomain(d));
}

TEST(GeometryDomain, PointInPolygonAndArea) {
  const std::vector<Vec2> sq{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_TRUE(pointInPolygon(sq, {0.5, 0.5}));
  EXPECT_FALSE(pointInPolygon(sq, {1.5, 0.5}));
  EXPECT_DOUBLE_EQ(signedArea(sq), 1.0);
}

TEST(GeometryDomain, HoleTouchingOuterIsRejected) {
  Domain d;
  d.outer = rectangle(0, 0, 4, 4);
  d.holes = {circle(3, 2, 1)};  // tangent to x = 4 at (4, 2)
  expectInvalid(d, ErrorCode::SelfIntersectingContour, "near (4, 2)");
}

#include <gtest/gtest.h>

#include <cmath>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/discretize.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/mesh_metric_field.h"
#include "anisomesh/pipeline/remesh_geometry.h"

using namespace anisomesh;

namespace {

CaseSpec caseWith(const std::string& controlSpace, const std::string& sources) {
  return parseCaseJson(R"({"domain": {"outer": [{"type": "polyline", "points": [[0,0],[10,0],[10,5],[0,5],[0,0]]}]},
                          "controlSpace": )" + controlSpace + R"(, "sources": )" + sources + "}");
}

const char* kRadial = R"([{"type": "radial", "center": [5, 2.5], "metric": {"alpha": 0, "h1": 0.05, "h2": 0.2}, "radius": 0.5}])";

// A 2x2 square split into 8 triangles around a centre-less grid, refs on the boundary.
Mesh squareMesh() {
  Mesh m;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) m.points.push_back(Vec3(i, j, 0));
  m.pointRefs.assign(9, 0);
  auto id = [](int i, int j) { return j * 3 + i; };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.triangleRefs.assign(m.triangles.size(), 0);
  m.edges = {{id(0, 0), id(1, 0)}, {id(1, 0), id(2, 0)}, {id(2, 2), id(1, 2)}};
  m.edgeRefs = {5, 5, 6};
  return m;
}

}  // namespace

TEST(CaseControlSpace, BackgroundAndRadialWithoutGradation) {
  const auto cs = buildCaseControlSpace(caseWith(R"({"hmax": 0.5})", kRadial));
  EXPECT_TRUE(cs->bounds().contains(Vec2(0, 0)));
  EXPECT_TRUE(cs->bounds().contains(Vec2(10, 5)));
  const Metric far = cs->metricAt({1, 1});
  EXPECT_NEAR(far.sizeAlong({1, 0}), 0.5, 1e-12);
  EXPECT_NEAR(far.sizeAlong({0, 1}), 0.5, 1e-12);
  const Metric in = cs->metricAt({5.2, 2.5});
  EXPECT_NEAR(in.sizeAlong({1, 0}), 0.05, 1e-12);
  EXPECT_NEAR(in.sizeAlong({0, 1}), 0.2, 1e-12);
  // No gradation: the source ends at its radius.
  EXPECT_NEAR(cs->metricAt({5.6, 2.5}).sizeAlong({1, 0}), 0.5, 1e-12);
}

TEST(CaseControlSpace, GradationSlopeFollowsPaperEq4) {
  EXPECT_NEAR(gradationSlope(2.0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(gradationSlope(1.0), 0.0, 1e-15);
  const auto cs = buildCaseControlSpace(caseWith(R"({"hmax": 0.5, "gradation": 2})", kRadial));
  // At distance radius + 0.3 the x-size grew by slope * 0.3.
  EXPECT_NEAR(cs->metricAt({5.8, 2.5}).sizeAlong({1, 0}), 0.05 + 0.3 * 2.0 / 3.0, 1e-9);
  // Along a ray the requested size never grows faster than the slope.
  const double a = gradationSlope(2.0);
  double prev = cs->metricAt({5.5, 2.5}).sizeAlong({1, 0});
  for (double x = 5.51; x < 9.9; x += 0.01) {
    const double h = cs->metricAt({x, 2.5}).sizeAlong({1, 0});
    EXPECT_LE(h - prev, a * 0.01 * (1 + 1e-9)) << x;
    prev = h;
  }
  EXPECT_NEAR(prev, 0.5, 1e-12);  // capped by hmax
}

TEST(CaseControlSpace, SegmentSourceAndHminClamp) {
  const auto cs = buildCaseControlSpace(caseWith(
      R"({"hmax": 1, "hmin": 0.1})",
      R"([{"type": "segment", "p1": [1, 1], "p2": [9, 1], "metric": {"alpha": 0, "h1": 0.5, "h2": 0.01}, "radius": 0.2}])"));
  const Metric m = cs->metricAt({4, 1.1});
  EXPECT_NEAR(m.sizeAlong({1, 0}), 0.5, 1e-9);
  EXPECT_NEAR(m.sizeAlong({0, 1}), 0.1, 1e-9);  // 0.01 clamped to hmin
  EXPECT_NEAR(cs->metricAt({4, 2}).sizeAlong({0, 1}), 1.0, 1e-12);
}

TEST(CaseControlSpace, AnalyticFields) {
  const auto cs = buildCaseControlSpace(caseWith(R"({"hmax": 0.2, "gradation": 2})", R"([
      {"type": "analytic", "field": "boundary_layer", "p1": [0, 0], "p2": [10, 0], "h0": 0.001, "hTangent": 0.1, "thickness": 0.5},
      {"type": "analytic", "field": "shear_layer_circle", "center": [5, 2.5], "radius": 1, "h0": 0.002, "hTangent": 0.05, "thickness": 0.1},
      {"type": "analytic", "field": "point", "center": [8, 4], "h0": 0.003, "growth": 0.5}])"));
  const Metric wall = cs->metricAt({2, 0});
  EXPECT_NEAR(wall.sizeAlong({0, 1}), 0.001, 1e-12);
  EXPECT_NEAR(wall.sizeAlong({1, 0}), 0.1, 1e-12);
  EXPECT_GE(wall.aspectRatio(), 100 - 1e-9);
  EXPECT_NEAR(cs->metricAt({2, 0.25}).sizeAlong({0, 1}), 0.001 + 0.099 * 0.5, 1e-12);
  // On the circle: fine radially, long tangentially.
  const Vec2 onCircle(5 + std::cos(0.7), 2.5 + std::sin(0.7));
  const Metric s = cs->metricAt(onCircle);
  EXPECT_NEAR(s.sizeAlong(Vec2(std::cos(0.7), std::sin(0.7))), 0.002, 1e-12);
  EXPECT_NEAR(s.sizeAlong(Vec2(-std::sin(0.7), std::cos(0.7))), 0.05, 1e-12);
  EXPECT_NEAR(cs->metricAt({8, 4}).sizeAlong({1, 0}), 0.003, 1e-12);
  EXPECT_NEAR(cs->metricAt({8.1, 4}).sizeAlong({1, 0}), 0.003 + 0.05, 1e-12);
}

TEST(CaseControlSpace, BoundaryLayerExampleHasAspectRatio100) {
  const CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/boundary_layer.json");
  const auto cs = buildCaseControlSpace(spec);
  EXPECT_GE(cs->metricAt({2, 0}).aspectRatio(), 100 - 1e-9);
}

TEST(MeshMetricField, InterpolatesLinearlyAndClampsOutside) {
  const Mesh m = squareMesh();
  // Mt linear in x: sizes 0.1 at x = 0, 0.1 / (1 + x) ... via Mt = (10 + 5x) I.
  std::vector<Metric> metrics;
  for (const Vec3& p : m.points) metrics.push_back(Metric::fromTransform(Mat2::Identity() * (10 + 5 * p.x() + 2 * p.y())));
  const TriangleMeshMetricField f(m, metrics);
  for (const Vec2& q : {Vec2(0.3, 0.2), Vec2(1.7, 1.1), Vec2(1.0, 1.0), Vec2(2, 2), Vec2(0.01, 1.99)}) {
    const double expected = 10 + 5 * q.x() + 2 * q.y();
    EXPECT_NEAR(f.metricAt(q).transform()(0, 0), expected, 1e-9) << q.transpose();
    EXPECT_NEAR(f.metricAt(q).transform()(0, 1), 0.0, 1e-12);
  }
  // Outside: the nearest boundary value.
  EXPECT_NEAR(f.metricAt({3, 1}).transform()(0, 0), 10 + 10 + 2, 1e-9);
  EXPECT_THROW(TriangleMeshMetricField(m, std::vector<Metric>(3)), Error);
}

TEST(RemeshGeometry, BoundaryLoopsKeepRefsAndOrientation) {
  const Mesh m = squareMesh();
  const auto loops = boundaryLoopsFromMesh(m);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].points.size(), 8u);
  EXPECT_GT(signedArea(loops[0].points), 0);
  int fives = 0, sixes = 0;
  for (size_t i = 0; i < 8; ++i) {
    const Vec2 a = loops[0].points[i], b = loops[0].points[(i + 1) % 8];
    if (loops[0].edgeRefs[i] == 5) {
      ++fives;
      EXPECT_EQ(a.y(), 0);
      EXPECT_EQ(b.y(), 0);
    }
    if (loops[0].edgeRefs[i] == 6) ++sixes;
  }
  EXPECT_EQ(fives, 2);
  EXPECT_EQ(sixes, 1);
  // Curves: split at the 4 corners and at ref changes.
  const Domain d = domainFromBoundaryLoops(loops);
  EXPECT_GE(d.outer.curves.size(), 5u);
  EXPECT_NO_THROW(validateDomain(d));
}

TEST(RemeshGeometry, HoleInMesh) {
  // A 3x3 grid of quads with the centre quad removed: one outer loop, one hole.
  Mesh m;
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 3; ++i) m.points.push_back(Vec3(i, j, 0));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      if (!(i == 1 && j == 1)) m.quads.push_back({j * 4 + i, j * 4 + i + 1, (j + 1) * 4 + i + 1, (j + 1) * 4 + i});
  const auto loops = boundaryLoopsFromMesh(m);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].points.size(), 12u);
  EXPECT_NEAR(signedArea(loops[0].points), 9.0, 1e-12);
  EXPECT_NEAR(signedArea(loops[1].points), -1.0, 1e-12);
  EXPECT_NO_THROW(validateDomain(domainFromBoundaryLoops(loops)));
}

TEST(RemeshGeometry, OpenBoundaryIsReported) {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  m.edges = {{0, 1}, {1, 2}, {2, 3}};
  m.edgeRefs = {1, 1, 1};
  try {
    boundaryLoopsFromMesh(m);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::OpenContour);
    EXPECT_NE(std::string(e.what()).find("has 1 boundary edges"), std::string::npos) << e.what();
  }
  m.edges.push_back({3, 0});
  EXPECT_EQ(boundaryLoopsFromMesh(m).size(), 1u);
}

TEST(RemeshGeometry, ClampMetricSizes) {
  const std::vector<Metric> in{Metric::fromSizes(0.4, 0.001, 5.0), Metric::isotropic(0.5)};
  const auto out = clampMetricSizes(in, 0.01, 1.0);
  EXPECT_NEAR(out[0].sizeAlong({std::cos(0.4), std::sin(0.4)}), 0.01, 1e-12);
  EXPECT_NEAR(out[0].sizeAlong({-std::sin(0.4), std::cos(0.4)}), 1.0, 1e-12);
  EXPECT_NEAR(out[1].sizeAlong({1, 0}), 0.5, 1e-12);
}

TEST(CaseControlSpace, ExampleBoundariesHaveUnitMetricSegments) {
  for (const char* name : {"point_source.json", "fig7_rect_holes_dr2.json", "shear_layer.json"}) {
    SCOPED_TRACE(name);
    const CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + name);
    const auto cs = buildCaseControlSpace(spec);
    std::vector<const Contour*> contours{&spec.domain.outer};
    for (const Contour& h : spec.domain.holes) contours.push_back(&h);
    for (const Contour* c : contours)
      for (const CurveUse& u : c->curves) {
        const double total = metricLength(*u.curve, *cs);
        if (total < 5 || !u.curve->breakpoints().empty()) continue;  // rounding dominates short curves
        const auto ts = discretizeCurve(*u.curve, *cs);
        for (size_t i = 0; i + 1 < ts.size(); ++i) {
          const double m = metricLength(*u.curve, *cs, ts[i], ts[i + 1]);
          EXPECT_GE(m, 0.9);
          EXPECT_LE(m, 1.1);
        }
      }
  }
}

TEST(RemeshGeometry, DiscretizeUnderMeshMetricField) {
  // The remesh geometry path without the mesher: boundary loops -> domain -> discretization.
  const Mesh m = squareMesh();
  std::vector<Metric> metrics;
  for (const Vec3& p : m.points) metrics.push_back(Metric::isotropic(0.05 + 0.05 * p.x()));
  const TriangleMeshMetricField field(m, metrics);
  const Domain d = domainFromBoundaryLoops(boundaryLoopsFromMesh(m));
  ASSERT_NO_THROW(validateDomain(d));
  const auto loops = discretizeDomain(d, field);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_GT(loops[0].points.size(), 40u);
  // Corners stay boundary points and refs are carried to the new edges.
  for (const Vec2& corner : {Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)}) {
    bool found = false;
    for (const Vec2& p : loops[0].points) found = found || (p - corner).norm() < 1e-12;
    EXPECT_TRUE(found) << corner.transpose();
  }
  int fives = 0;
  for (size_t i = 0; i < loops[0].points.size(); ++i)
    if (loops[0].edgeRefs[i] == 5) {
      ++fives;
      EXPECT_NEAR(loops[0].points[i].y(), 0.0, 1e-14);
    }
  EXPECT_GT(fives, 10);
}

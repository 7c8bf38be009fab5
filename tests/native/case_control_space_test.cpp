#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "anisomesh/boundary/discretize.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/mesh_metric_field.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/pipeline/remesh_geometry.h"

using namespace anisomesh;

namespace {

CaseSpec caseWith(const std::string& controlSpace, const std::string& sources) {
  return parseCaseJson(R"({"domain": {"outer": [{"type": "polyline", "points": [[0,0],[10,0],[10,5],[0,5],[0,0]]}]},
                          "controlSpace": )" +
                       controlSpace + R"(, "sources": )" + sources + "}");
}

const char* kRadial =
    R"([{"type": "radial", "center": [5, 2.5], "metric": {"alpha": 0, "h1": 0.05, "h2": 0.2}, "radius": 0.5}])";

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

// Relative closeness: the quadtree interpolates between its nodes.
::testing::AssertionResult near(double value, double expected, double relative) {
  if (std::abs(value - expected) <= relative * std::abs(expected)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << value << " is not within " << relative * 100 << "% of " << expected;
}

TEST(CaseControlSpace, HmaxDefaultAndRadialWithoutGradation) {
  const auto cs = buildCaseControlSpace(caseWith(R"({"hmax": 0.5})", kRadial));
  EXPECT_STREQ(cs->kindName(), "quadtree");
  EXPECT_TRUE(cs->bounds().contains(Vec2(0, 0)));
  EXPECT_TRUE(cs->bounds().contains(Vec2(10, 5)));
  const Metric far = cs->metricAt({1, 1});
  EXPECT_NEAR(far.sizeAlong({1, 0}), 0.5, 1e-9);
  EXPECT_NEAR(far.sizeAlong({0, 1}), 0.5, 1e-9);
  const Metric in = cs->metricAt({5.2, 2.5});
  EXPECT_TRUE(near(in.sizeAlong({1, 0}), 0.05, 0.02));
  EXPECT_TRUE(near(in.sizeAlong({0, 1}), 0.2, 0.02));
  // No gradation: the source ends near its radius (within a quarter radius), abruptly.
  EXPECT_NEAR(cs->metricAt({5.7, 2.5}).sizeAlong({1, 0}), 0.5, 1e-9);
  EXPECT_NEAR(cs->metricAt({5, 3.2}).sizeAlong({0, 1}), 0.5, 1e-9);
}

TEST(CaseControlSpace, BackgroundKindBuildsABackgroundMesh) {
  const auto cs = buildCaseControlSpace(caseWith(R"({"kind": "background", "hmax": 0.5})", kRadial));
  EXPECT_STREQ(cs->kindName(), "background");
  EXPECT_TRUE(near(cs->metricAt({5.1, 2.5}).sizeAlong({1, 0}), 0.05, 0.02));
  EXPECT_NEAR(cs->metricAt({1, 1}).sizeAlong({1, 0}), 0.5, 1e-9);
}

TEST(CaseControlSpace, GradationBoundsTheGrowthOfSizes) {
  const auto cs = buildCaseControlSpace(caseWith(R"({"hmax": 0.5, "gradation": 2})", kRadial));
  // Along a ray the requested size stays below the line of slope a_max (eq. 4) from the
  // source's edge (the smoothing bounds it at the control nodes; interpolating Mt inside
  // a leaf bends h between them, hence the slack), up to hmax.
  const double a = gradationSlope(2.0);
  double h = 0.0;
  for (double x = 5.5; x < 9.9; x += 0.02) {
    h = cs->metricAt({x, 2.5}).sizeAlong({1, 0});
    EXPECT_LE(h, 0.05 + 1.05 * a * (x - 5.5) + 0.02) << x;
  }
  EXPECT_NEAR(h, 0.5, 1e-9);  // capped by hmax
  // Without gradation the same point is coarse; with it, graded.
  EXPECT_LT(cs->metricAt({6.0, 2.5}).sizeAlong({1, 0}), 0.45);
}

TEST(CaseControlSpace, SegmentSourceAndHminClamp) {
  const auto cs = buildCaseControlSpace(caseWith(
      R"({"hmax": 1, "hmin": 0.1})",
      R"([{"type": "segment", "p1": [1, 1], "p2": [9, 1], "metric": {"alpha": 0, "h1": 0.5, "h2": 0.01}, "radius": 0.2}])"));
  const Metric m = cs->metricAt({4, 1.1});
  EXPECT_TRUE(near(m.sizeAlong({1, 0}), 0.5, 0.02));
  EXPECT_TRUE(near(m.sizeAlong({0, 1}), 0.1, 0.02));  // 0.01 clamped to hmin
  EXPECT_NEAR(cs->metricAt({4, 2}).sizeAlong({0, 1}), 1.0, 1e-9);
}

TEST(CaseControlSpace, PolylineAndNodeSources) {
  const auto cs = buildCaseControlSpace(caseWith(R"({"hmax": 1})", R"([
      {"type": "polyline", "points": [[1, 1], [3, 1], [3, 3]], "metric": {"h1": 0.05}, "radius": 0.1},
      {"type": "nodes", "points": [[8, 4]], "metrics": [{"alpha": 0, "h1": 0.02, "h2": 0.3}]}])"));
  EXPECT_TRUE(near(cs->metricAt({2, 1}).sizeAlong({1, 0}), 0.05, 0.03));
  EXPECT_TRUE(near(cs->metricAt({3, 2}).sizeAlong({0, 1}), 0.05, 0.03));
  // A radius-0 node reaches the control nodes of its own small leaf only.
  EXPECT_LT(cs->metricAt({8, 4}).sizeAlong({1, 0}), 0.03);
  EXPECT_NEAR(cs->metricAt({6, 1}).sizeAlong({1, 0}), 1.0, 1e-9);
}

TEST(CaseControlSpace, AnalyticFields) {
  const CaseSpec spec = caseWith(R"({"hmax": 0.2, "gradation": 2, "maxLevel": 12})", R"([
      {"type": "analytic", "field": "boundary_layer", "p1": [0, 0], "p2": [10, 0], "h0": 0.001, "hTangent": 0.1, "thickness": 0.5},
      {"type": "analytic", "field": "shear_layer_circle", "center": [5, 2.5], "radius": 1, "h0": 0.002, "hTangent": 0.05, "thickness": 0.1},
      {"type": "analytic", "field": "point", "center": [8, 4], "h0": 0.003, "growth": 0.5}])");
  // The analytic function itself.
  const MetricFunction f = caseAnalyticMetric(spec);
  EXPECT_NEAR(f({2, 0}).sizeAlong({0, 1}), 0.001, 1e-12);
  EXPECT_NEAR(f({2, 0}).sizeAlong({1, 0}), 0.1, 1e-12);
  EXPECT_NEAR(f({2, 0.25}).sizeAlong({0, 1}), 0.001 + 0.099 * 0.5, 1e-12);
  EXPECT_NEAR(f({8.1, 4}).sizeAlong({1, 0}), 0.003 + 0.05, 1e-12);
  // The structure resolves it.
  const auto cs = buildCaseControlSpace(spec);
  const Metric wall = cs->metricAt({2, 0});
  // Refinement threshold 0.1 and the smallest leaf (no hmin: hmax / 100) bound the error.
  EXPECT_TRUE(near(wall.sizeAlong({0, 1}), 0.001, 0.15));
  EXPECT_TRUE(near(wall.sizeAlong({1, 0}), 0.1, 0.03));
  EXPECT_GE(wall.aspectRatio(), 85);
  const Vec2 onCircle(5 + std::cos(0.7), 2.5 + std::sin(0.7));
  const Metric s = cs->metricAt(onCircle);
  // Across the layer the size changes by ~half of h0 over one smallest leaf (maxLevel 12:
  // 0.0025), which bounds the interpolation error there.
  EXPECT_TRUE(near(s.sizeAlong(Vec2(std::cos(0.7), std::sin(0.7))), 0.002, 0.25));
  EXPECT_TRUE(near(s.sizeAlong(Vec2(-std::sin(0.7), std::cos(0.7))), 0.05, 0.1));
  EXPECT_TRUE(near(cs->metricAt({8, 4}).sizeAlong({1, 0}), 0.003, 0.1));
}

TEST(CaseControlSpace, ExpressionField) {
  const CaseSpec spec = caseWith(R"({"hmax": 1})", R"j([
      {"type": "analytic", "field": "expression", "alpha": "atan2(y, x)", "h1": "0.01 + 0.1 * abs(x - 5)", "h2": 0.5}])j");
  const MetricFunction f = caseAnalyticMetric(spec);
  EXPECT_NEAR(f({5, 1}).sizeAlong({std::cos(std::atan2(1.0, 5.0)), std::sin(std::atan2(1.0, 5.0))}), 0.01, 1e-12);
  EXPECT_NEAR(f({7, 1}).sizeAlong({-std::sin(std::atan2(1.0, 7.0)), std::cos(std::atan2(1.0, 7.0))}), 0.5, 1e-12);
  const auto cs = buildCaseControlSpace(spec);
  EXPECT_TRUE(near(cs->metricAt({5, 2}).sizes().h1, 0.01, 0.05));
  // Errors name the JSON path and the column.
  try {
    caseWith(R"({"hmax": 1})", R"([{"type": "analytic", "field": "expression", "h1": "0.1 + z"}])");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ParseError);
    EXPECT_NE(std::string(e.what()).find("sources[0].h1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("column 7"), std::string::npos) << e.what();
  }
  // A size that is not positive somewhere: InvalidMetric naming the source.
  try {
    buildCaseControlSpace(
        caseWith(R"({"hmax": 1})", R"([{"type": "analytic", "field": "expression", "h1": "x - 5"}])"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidMetric);
    EXPECT_NE(std::string(e.what()).find("sources[0]"), std::string::npos) << e.what();
  }
}

TEST(CaseControlSpace, BoundaryLayerExampleHasAspectRatio100) {
  const CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/boundary_layer.json");
  const auto cs = buildCaseControlSpace(spec);
  EXPECT_GE(caseAnalyticMetric(spec)({2, 0}).aspectRatio(), 100 - 1e-9);
  EXPECT_GE(cs->metricAt({2, 0}).aspectRatio(), 95);
}

TEST(MeshMetricField, InterpolatesLinearlyAndClampsOutside) {
  const Mesh m = squareMesh();
  // Mt linear in x: sizes 0.1 at x = 0, 0.1 / (1 + x) ... via Mt = (10 + 5x) I.
  std::vector<Metric> metrics;
  for (const Vec3& p : m.points)
    metrics.push_back(Metric::fromTransform(Mat2::Identity() * (10 + 5 * p.x() + 2 * p.y())));
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

// Outside the mesh the field takes the nearest triangle of all (of equal distances the
// lowest index), whatever the grid: checked against a search over every boundary edge, on a
// rotated square of thin graded triangles queried all over its bounding box and beyond
// (a search stopping one ring of cells past the first candidate misses some). The square is
// convex, so a point outside has its nearest mesh point on a boundary edge, and the field is
// linear on each triangle and continuous, so the value there does not depend on which of the
// triangles holding that point answers: the reference needs the boundary edges only (the
// search over every edge of every triangle took 15 s under the sanitizers).
TEST(MeshMetricField, OutsideTakesTheNearestTriangleOfAll) {
  Mesh m;
  const double c = std::cos(0.5235987755982988), s = std::sin(0.5235987755982988);
  std::vector<double> vs{0.0};
  while (vs.back() < 1.0) vs.push_back(std::min(1.0, vs.back() + 0.002 + 0.05 * std::abs(vs.back() - 0.5)));
  const int nu = 61, nv = int(vs.size());
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = i / double(nu - 1) - 0.5, v = vs[size_t(j)] - 0.5;
      m.points.push_back(Vec3(0.5 + c * u - s * v, 0.5 + s * u + c * v, 0));
    }
  auto id = [&](int i, int j) { return j * nu + i; };
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  std::vector<Metric> metrics;  // a different Mt at every vertex
  for (size_t k = 0; k < m.points.size(); ++k)
    metrics.push_back(Metric::fromTransform(Mat2::Identity() * (10.0 + double(k))));
  const TriangleMeshMetricField f(m, metrics);
  auto pt = [&](int v) { return Vec2(m.points[size_t(v)].head<2>()); };
  // Boundary edges (in one triangle only) with their triangle.
  std::map<std::pair<int, int>, std::pair<int, size_t>> edgeUse;  // sorted edge -> (uses, triangle)
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = m.triangles[t][size_t(e)], b = m.triangles[t][size_t((e + 1) % 3)];
      auto& use = edgeUse[{std::min(a, b), std::max(a, b)}];
      use.first++, use.second = t;
    }
  std::vector<std::pair<std::pair<int, int>, size_t>> boundary;
  for (const auto& [edge, use] : edgeUse)
    if (use.first == 1) boundary.push_back({edge, use.second});
  ASSERT_EQ(boundary.size(), size_t(2 * (nu - 1) + 2 * (nv - 1)));
  auto bary = [&](const std::array<int, 3>& t, const Vec2& q) {
    const Vec2 a = pt(t[0]), b = pt(t[1]), d = pt(t[2]);
    const double det = (b.x() - a.x()) * (d.y() - a.y()) - (b.y() - a.y()) * (d.x() - a.x());
    const double l1 = ((q.x() - a.x()) * (d.y() - a.y()) - (q.y() - a.y()) * (d.x() - a.x())) / det;
    const double l2 = ((b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x())) / det;
    return Vec3(1.0 - l1 - l2, l1, l2);
  };
  int outside = 0;
  for (int gy = 0; gy <= 40; ++gy)
    for (int gx = 0; gx <= 40; ++gx) {
      const Vec2 p(-0.4 + 1.8 * gx / 40.0, -0.4 + 1.8 * gy / 40.0);
      // Inside the (convex) square: its coordinates along the square's axes.
      const double u = c * (p.x() - 0.5) + s * (p.y() - 0.5), v = -s * (p.x() - 0.5) + c * (p.y() - 0.5);
      if (std::abs(u) <= 0.5 + 1e-9 && std::abs(v) <= 0.5 + 1e-9) continue;
      size_t best = 0;
      double bestDist = -1;
      Vec2 bestPoint = p;
      for (const auto& [edge, t] : boundary) {
        const Vec2 a = pt(edge.first), b = pt(edge.second);
        const double l = std::min(1.0, std::max(0.0, (p - a).dot(b - a) / (b - a).squaredNorm()));
        const Vec2 q = a + l * (b - a);
        if (bestDist < 0 || (q - p).squaredNorm() < bestDist) best = t, bestDist = (q - p).squaredNorm(), bestPoint = q;
      }
      ++outside;
      const auto& tri = m.triangles[best];
      const Vec3 l = bary(tri, bestPoint).cwiseMax(0.0);
      double expected = 0;
      for (int k = 0; k < 3; ++k) expected += l[k] * (10.0 + tri[size_t(k)]);
      expected /= l.sum();
      EXPECT_NEAR(f.metricAt(p).transform()(0, 0), expected, 1e-9) << p.transpose();
    }
  EXPECT_GT(outside, 500);
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
  const auto field = buildRemeshControlSpace(m, metrics);
  const Domain d = domainFromBoundaryLoops(boundaryLoopsFromMesh(m));
  ASSERT_NO_THROW(validateDomain(d));
  const auto loops = discretizeDomain(d, *field);
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

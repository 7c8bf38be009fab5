#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "anisomesh/io/case_json.h"
#include "anisomesh/io/report_json.h"
#include "anisomesh/pipeline/pipeline.h"
#include "mesh_test_util.h"

using namespace anisomesh;
using namespace meshtest;

namespace {

const Box2 kQuadsUnit{{0.0, 0.0}, {1.0, 1.0}};

Metric quadLayer(const Vec2& p) {
  return Metric::fromSizes(0.0, 0.05, std::min(0.05, 0.005 + 0.2 * std::fabs(p.y() - 0.5)));
}

std::vector<BoundaryLoop> domain(const ControlSpace& cs) {
  return {metricPolygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, cs), circleLoop({0.3, 0.3}, 0.1, 24, true)};
}

bool convexCcw(const Mesh& m, const std::array<int, 4>& q) {
  for (int i = 0; i < 4; ++i)
    if (orient2d(m.params[q[(i + 3) % 4]], m.params[q[i]], m.params[q[(i + 1) % 4]]) <= 0.0) return false;
  return true;
}

}  // namespace

TEST(MeshQuads, QuadDominant) {
  AnalyticControlSpace cs(kQuadsUnit, quadLayer);
  const auto loops = domain(cs);
  const Mesh tri = meshPlanarBoundary(loops, cs);
  PlanarMesherOptions opt;
  opt.quads = true;
  const Mesh m = meshPlanarBoundary(loops, cs, opt);
  checkPlanarMesh(m, loops);
  EXPECT_EQ(m.vertexCount(), tri.vertexCount());
  EXPECT_EQ(m.triangles.size() + 2 * m.quads.size(), tri.triangles.size());
  EXPECT_GE(2.0 * m.quads.size(), 0.8 * tri.triangles.size()) << "not quad dominant";
  EXPECT_EQ(m.quadRefs.size(), m.quads.size());
  EXPECT_EQ(m.triangleRefs.size(), m.triangles.size());
  for (const auto& q : m.quads) EXPECT_TRUE(convexCcw(m, q));
  const QualityReport r = measureQuality(m, cs);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_EQ(r.degenerate, 0);
  EXPECT_GE(r.quadQualityMin, opt.minQuadQuality);
  std::cout << "quad dominant: " << qualityReportToJson(r).dump() << "\n";
  EXPECT_TRUE(sameMesh(m, meshPlanarBoundary(loops, cs, opt)));
}

TEST(MeshQuads, AllQuads) {
  AnalyticControlSpace cs(kQuadsUnit, quadLayer);
  const auto loops = domain(cs);
  PlanarMesherOptions opt;
  opt.quads = true;
  const Mesh qd = meshPlanarBoundary(loops, cs, opt);
  opt.allQuads = true;
  const Mesh m = meshPlanarBoundary(loops, cs, opt);
  EXPECT_TRUE(m.triangles.empty());
  EXPECT_EQ(m.quads.size(), 3 * qd.triangles.size() + 4 * qd.quads.size());
  EXPECT_EQ(m.edges.size(), 2 * qd.edges.size());
  EXPECT_EQ(m.params.size(), m.points.size());
  // Euler: V - E + F = 1 - holes for a planar domain (counting elements as faces).
  std::vector<std::uint64_t> keys;
  double area = 0.0;
  for (const auto& q : m.quads) {
    EXPECT_TRUE(convexCcw(m, q));
    for (int i = 0; i < 4; ++i) keys.push_back(key(q[i], q[(i + 1) % 4]));
    area += 0.5 * (orient2d(m.params[q[0]], m.params[q[1]], m.params[q[2]]) +
                   orient2d(m.params[q[0]], m.params[q[2]], m.params[q[3]]));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  EXPECT_EQ(static_cast<long>(m.vertexCount()) - static_cast<long>(keys.size()) + static_cast<long>(m.quads.size()),
            1 - 1);
  EXPECT_NEAR(area, domainArea(loops), 1e-9);
  for (const auto& e : m.edges) EXPECT_TRUE(std::binary_search(keys.begin(), keys.end(), key(e[0], e[1])));
  const QualityReport r = measureQuality(m, cs);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_EQ(r.triangles, 0);
  std::cout << "all quads: " << qualityReportToJson(r).dump() << "\n";
}

// The all-quad split puts a curved contour's new points on the curve (the curve's point at
// the segment's middle parameter), for planar cases as for surface patches: every boundary
// vertex of a hole's circle lies on it, and the straight sides keep their straight midpoints.
TEST(MeshQuads, AllQuadBoundaryPointsLieOnTheirCurves) {
  const CaseSpec spec = parseCaseJson(R"({
    "domain": {"outer": [{"type": "polyline", "points": [[0,0],[2,0],[2,1],[0,1],[0,0]]}],
               "holes": [[{"type": "circle", "center": [1, 0.5], "radius": 0.25, "ref": 5}]]},
    "controlSpace": {"hmax": 0.1}, "options": {"allQuads": true}})");
  const Mesh m = meshCase(spec);
  ASSERT_FALSE(m.quads.empty());
  int onCircle = 0;
  for (size_t e = 0; e < m.edges.size(); ++e) {
    if (m.edgeRefs[e] != 5) continue;
    for (int v : m.edges[e]) {
      EXPECT_NEAR((m.params[size_t(v)] - Vec2(1, 0.5)).norm(), 0.25, 1e-12) << "vertex " << v;
      ++onCircle;
    }
  }
  EXPECT_GT(onCircle, 40);
  for (size_t e = 0; e < m.edges.size(); ++e)
    if (m.edgeRefs[e] != 5)
      for (int v : m.edges[e]) {
        const Vec2 p = m.params[size_t(v)];
        EXPECT_TRUE(p.x() == 0 || p.x() == 2 || p.y() == 0 || p.y() == 1) << p.transpose();
      }
}

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "anisomesh/io/report_json.h"
#include "anisomesh/mesh/element_edges.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "mesh_test_util.h"

using namespace anisomesh;
using namespace meshtest;

// Hand-made mesh: one equilateral triangle in the identity metric scaled to unit edges,
// one flat and one inverted triangle, one unit square.
TEST(MeshQuality, ReportOnAHandMadeMesh) {
  Mesh m;
  const double h = std::sqrt(3.0) / 2.0;
  m.params = {{0, 0}, {1, 0}, {0.5, h}, {2, 0}, {3, 0}, {3, 1}, {2, 1}};
  for (const auto& p : m.params) m.points.emplace_back(p.x(), p.y(), 0.0);
  m.triangles = {{0, 1, 2}, {0, 1, 3}, {1, 0, 2}};
  m.quads = {{3, 4, 5, 6}};
  UniformControlSpace cs({{-1, -1}, {4, 2}}, Metric());
  const QualityReport r = measureQuality(m, cs);
  EXPECT_EQ(r.vertices, 7);
  EXPECT_EQ(r.triangles, 3);
  EXPECT_EQ(r.quads, 1);
  EXPECT_EQ(r.inverted, 1);
  EXPECT_EQ(r.degenerate, 1);
  EXPECT_NEAR(r.quadQualityMin, 1.0, 1e-12);
  EXPECT_NEAR(r.triangleQualityMin, -1.0, 1e-12);
  EXPECT_NEAR(r.edgeLengthMin, 1.0, 1e-12);
  EXPECT_NEAR(r.edgeLengthMax, 2.0, 1e-12);  // the flat triangle's edge 0-3
  EXPECT_EQ(std::accumulate(r.qualityHistogram.begin(), r.qualityHistogram.end(), 0), 4);
  EXPECT_EQ(r.qualityHistogram[9], 2);  // equilateral and square
  const nlohmann::json j = qualityReportToJson(r);
  EXPECT_EQ(j["triangles"], 3);
  EXPECT_EQ(j["inverted"], 1);
  EXPECT_TRUE(j["quality"].contains("histogram"));
  EXPECT_TRUE(j["edgeLength"].contains("fractionWithinSqrt2"));
  EXPECT_TRUE(j["timings"].contains("insertion"));
}

// The per-item measures are what the report summarizes: same edges, same means, the
// hand-made mesh's known values item by item, the smallest requested size per vertex.
TEST(MeshQuality, PerItemMeasuresAgreeWithTheReport) {
  Mesh m;
  const double h = std::sqrt(3.0) / 2.0;
  m.params = {{0, 0}, {1, 0}, {0.5, h}, {2, 0}, {3, 0}, {3, 1}, {2, 1}};
  for (const auto& p : m.params) m.points.emplace_back(p.x(), p.y(), 0.0);
  m.triangles = {{0, 1, 2}, {0, 1, 3}, {1, 0, 2}};
  m.quads = {{3, 4, 5, 6}};
  UniformControlSpace cs({{-1, -1}, {4, 2}}, Metric::fromSizes(0.0, 0.5, 0.25));
  ElementMeasures items;
  const QualityReport r = measureQuality(m, cs, &items);
  ASSERT_EQ(items.edges.size(), static_cast<size_t>(r.edges));
  EXPECT_EQ(items.edges, distinctElementEdges(m));
  for (size_t e = 0; e + 1 < items.edges.size(); ++e) {
    EXPECT_LT(items.edges[e][0], items.edges[e][1]);
    EXPECT_LT(items.edges[e], items.edges[e + 1]);
  }
  ASSERT_EQ(items.edgeLength.size(), items.edges.size());
  ASSERT_EQ(items.quality.size(), 4u);
  const double lmean = std::accumulate(items.edgeLength.begin(), items.edgeLength.end(), 0.0) / items.edgeLength.size();
  EXPECT_NEAR(lmean, r.edgeLengthMean, 1e-12);
  EXPECT_NEAR(std::accumulate(items.quality.begin(), items.quality.end(), 0.0) / 4, r.qualityMean, 1e-12);
  EXPECT_NEAR(items.quality[2], r.triangleQualityMin, 1e-12);  // the inverted triangle
  // Edge 0-1 (length 1 along x, size 0.5 along x): metric length 2.
  const auto it = std::find(items.edges.begin(), items.edges.end(), std::array<int, 2>{0, 1});
  ASSERT_NE(it, items.edges.end());
  EXPECT_NEAR(items.edgeLength[it - items.edges.begin()], 2.0, 1e-12);
  ASSERT_EQ(items.vertexMinSize.size(), 7u);
  for (double s : items.vertexMinSize) EXPECT_NEAR(s, 0.25, 1e-12);
}

// Edge lengths are measured in the metric: a mesh built for h = 0.1 measured against
// h = 0.05 has edges twice as long.
TEST(MeshQuality, MetricScalesLengths) {
  UniformControlSpace cs01({{0, 0}, {1, 1}}, Metric::isotropic(0.1));
  UniformControlSpace cs005({{0, 0}, {1, 1}}, Metric::isotropic(0.05));
  const Mesh m = meshPlanarBoundary({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 10)}, cs01);
  const QualityReport a = measureQuality(m, cs01), b = measureQuality(m, cs005);
  EXPECT_NEAR(b.edgeLengthMean, 2.0 * a.edgeLengthMean, 1e-9);
  EXPECT_NEAR(b.qualityMean, a.qualityMean, 1e-9);  // shape quality is scale free
}

// Metric areas of the boundary-only triangulation sum to the domain's metric area.
TEST(MeshQuality, TriangleMetricAreas) {
  UniformControlSpace cs({{0, 0}, {1, 1}}, Metric::fromSizes(0.3, 0.1, 0.2));
  PlanarMesherOptions opt;
  opt.boundaryOnly = true;
  const Mesh m = meshPlanarBoundary({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 5)}, cs, opt);
  const std::vector<double> areas = triangleMetricAreas(m, cs);
  ASSERT_EQ(areas.size(), m.triangles.size());
  EXPECT_NEAR(std::accumulate(areas.begin(), areas.end(), 0.0), 1.0 / (0.1 * 0.2), 1e-9);
  for (const double a : areas) EXPECT_GT(a, 0.0);
}

// One bucketing of the element edges serves the report's edges and its neighbour size
// ratio: each edge's owners in element order (quads numbered after the triangles), and the
// report's ratio is largestNeighbourSizeRatio's.
TEST(MeshQuality, ElementEdgesListEachEdgesOwnersInElementOrder) {
  Mesh m;
  m.params = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {2, 1}};
  for (const auto& p : m.params) m.points.emplace_back(p.x(), p.y(), 0.0);
  // Triangles 0 (0 1 3), 1 (0 3 2) and the quad 2 (1 4 5 3), whose area is 1 (ratio sqrt2 to 0.5).
  m.triangles = {{0, 1, 3}, {0, 3, 2}};
  m.quads = {{1, 4, 5, 3}};
  const ElementEdges ee = elementEdges(m);
  ASSERT_EQ(ee.edges, distinctElementEdges(m));
  ASSERT_EQ(ee.ownerStart.size(), ee.edges.size() + 1);
  auto ownersOf = [&](int a, int b) {
    const auto it = std::find(ee.edges.begin(), ee.edges.end(), std::array<int, 2>{a, b});
    if (it == ee.edges.end()) return std::vector<int>{-1};  // (no such edge: fails the comparison)
    const size_t k = size_t(it - ee.edges.begin());
    return std::vector<int>(ee.owners.begin() + ee.ownerStart[k], ee.owners.begin() + ee.ownerStart[k + 1]);
  };
  EXPECT_EQ(ownersOf(0, 3), (std::vector<int>{0, 1}));
  EXPECT_EQ(ownersOf(1, 3), (std::vector<int>{0, 2}));
  EXPECT_EQ(ownersOf(0, 2), (std::vector<int>{1}));
  EXPECT_EQ(ownersOf(4, 5), (std::vector<int>{2}));
  UniformControlSpace cs({{-1, -1}, {3, 2}}, Metric());
  EXPECT_DOUBLE_EQ(measureQuality(m, cs).largestNeighbourSizeRatio, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(largestNeighbourSizeRatio(m), std::sqrt(2.0));
}

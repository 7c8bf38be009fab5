// meshCase with the real control space and the section 3.2 updates; remesh with the
// background-mesh control space; pipeline statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/report_json.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "anisomesh/pipeline/pipeline.h"

using namespace anisomesh;

namespace {

CaseSpec exampleCase(const std::string& name) {
  return readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + name + ".json");
}

bool hasVertex(const Mesh& m, const Vec2& p, double tol) {
  for (const Vec3& q : m.points)
    if ((q.head<2>() - p).norm() <= tol) return true;
  return false;
}

std::vector<const Contour*> contoursOf(const Domain& d) {
  std::vector<const Contour*> out{&d.outer};
  for (const Contour& h : d.holes) out.push_back(&h);
  return out;
}

// Two holes of radius 0.5 whose gap is 0.02, in a coarse metric.
CaseSpec narrowChannel() {
  return parseCaseJson(R"({
    "domain": {"outer": [{"type": "polyline", "points": [[0, 0], [4, 0], [4, 2], [0, 2], [0, 0]], "ref": 1}],
               "holes": [[{"type": "circle", "center": [1.49, 1], "radius": 0.5, "ref": 2}],
                         [{"type": "circle", "center": [2.51, 1], "radius": 0.5, "ref": 3}]]},
    "controlSpace": {"hmin": 0.001, "hmax": 0.5, "gradation": 2}})");
}

CaseSpec coarseCircle() {
  return parseCaseJson(R"({
    "domain": {"outer": [{"type": "polyline", "points": [[-2, -2], [2, -2], [2, 2], [-2, 2], [-2, -2]], "ref": 1}],
               "holes": [[{"type": "circle", "center": [0, 0], "radius": 1, "ref": 2}]]},
    "controlSpace": {"hmax": 1.0}})");
}

// Largest deviation of a boundary edge of ref `ref` from the circle, relative to its length.
double circleChordDeviation(const Mesh& m, int ref, const Vec2& c, double r) {
  double worst = 0.0;
  for (size_t e = 0; e < m.edges.size(); ++e) {
    if (m.edgeRefs[e] != ref) continue;
    const Vec2 a = m.points[m.edges[e][0]].head<2>(), b = m.points[m.edges[e][1]].head<2>();
    worst = std::max(worst, (r - (0.5 * (a + b) - c).norm()) / (b - a).norm());
  }
  return worst;
}

void expectSameCaseMesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << i;
  for (size_t i = 0; i < a.triangles.size(); ++i) ASSERT_EQ(a.triangles[i], b.triangles[i]) << i;
  EXPECT_EQ(a.edges, b.edges);
}

}  // namespace

// One test per example (ctest runs them side by side); the goldens check each example's
// bytes across processes, the second run here within one (the caches it leaves).
class EveryExample : public testing::TestWithParam<const char*> {};

TEST_P(EveryExample, MeshesWithTheRealControlSpace) {
  const CaseSpec spec = exampleCase(GetParam());
  PipelineReport report;
  std::unique_ptr<AdaptiveControlSpace> cs;
  const Mesh mesh = meshCase(spec, &report, {}, &cs);
  ASSERT_TRUE(cs);
  EXPECT_TRUE(report.updatesConverged);
  const double scale = domainBounds(spec.domain).size().norm();
  // Every input boundary point (curve ends, polyline vertices) is a mesh vertex.
  std::map<int, double> curveLength, edgeLength;
  for (const Contour* c : contoursOf(spec.domain))
    for (const CurveUse& u : c->curves) {
      EXPECT_TRUE(hasVertex(mesh, u.start(), 1e-12 * scale)) << u.start().transpose();
      if (const auto* p = dynamic_cast<const PolylineCurve*>(u.curve.get())) {
        for (const Vec2& q : p->points()) EXPECT_TRUE(hasVertex(mesh, q, 1e-12 * scale)) << q.transpose();
      }
      curveLength[u.curve->ref()] += u.curve->length();
    }
  // Every boundary curve is covered by boundary edges (chords: slightly shorter on curves).
  for (size_t e = 0; e < mesh.edges.size(); ++e)
    edgeLength[mesh.edgeRefs[e]] += (mesh.points[mesh.edges[e][1]] - mesh.points[mesh.edges[e][0]]).norm();
  for (const auto& [ref, len] : curveLength) {
    EXPECT_LE(edgeLength[ref], len * (1 + 1e-9)) << "ref " << ref;
    EXPECT_GE(edgeLength[ref], len * 0.99) << "ref " << ref;
  }
  const QualityReport q = measureQuality(mesh, *cs);
  EXPECT_EQ(q.inverted, 0);
  EXPECT_EQ(q.degenerate, 0);
  EXPECT_GT(q.triangles, 100);
  // Deterministic.
  expectSameCaseMesh(mesh, meshCase(spec));
}

INSTANTIATE_TEST_SUITE_P(PipelineCase, EveryExample,
                         testing::Values("fig6_rect_holes_nosmooth", "fig7_rect_holes_dr8", "fig7_rect_holes_dr2",
                                         "boundary_layer", "shear_layer", "point_source", "expression_field"),
                         [](const testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

// Quality against the analytic metric the case asks for (not the structure's
// interpolation of it): the mesher follows the quadtree, the user wants the formula.
TEST(PipelineCase, BoundaryLayerQualityAgainstAnalyticMetric) {
  const CaseSpec spec = exampleCase("boundary_layer");
  std::unique_ptr<AdaptiveControlSpace> cs;
  const Mesh mesh = meshCase(spec, nullptr, {}, &cs);
  EXPECT_STREQ(cs->kindName(), "quadtree");
  const MetricFunction f = caseAnalyticMetric(spec);
  EXPECT_GE(f({2, 0}).aspectRatio(), 100 - 1e-9);
  const QualityReport q = measureQuality(mesh, AnalyticControlSpace(cs->bounds(), f));
  std::cout << "[ figures  ] boundary layer vs analytic: " << mesh.triangles.size()
            << " triangles, edges in [1/sqrt2, sqrt2] " << q.edgesWithinSqrt2 << ", mean Q " << q.qualityMean
            << ", min Q " << q.qualityMin << "\n";
  EXPECT_GE(q.edgesWithinSqrt2, 0.98);
  EXPECT_GE(q.qualityMean, 0.93);
  EXPECT_GE(q.qualityMin, 0.4);
}

TEST(PipelineCase, ShearLayerQualityAgainstAnalyticMetric) {
  const CaseSpec spec = exampleCase("shear_layer");
  std::unique_ptr<AdaptiveControlSpace> cs;
  const Mesh mesh = meshCase(spec, nullptr, {}, &cs);
  EXPECT_STREQ(cs->kindName(), "quadtree");
  const QualityReport q = measureQuality(mesh, AnalyticControlSpace(cs->bounds(), caseAnalyticMetric(spec)));
  std::cout << "[ figures  ] shear layer vs analytic: " << mesh.triangles.size()
            << " triangles, edges in [1/sqrt2, sqrt2] " << q.edgesWithinSqrt2 << ", mean Q " << q.qualityMean
            << ", min Q " << q.qualityMin << "\n";
  // Reached with the mesher's adaptation loop (collapse/split/swap/smooth in the metric):
  // 0.986 of the edges, mean Q 0.953, min Q 0.60.
  EXPECT_GE(q.edgesWithinSqrt2, 0.98);
  EXPECT_GE(q.qualityMean, 0.93);
  EXPECT_GE(q.qualityMin, 0.4);
}

TEST(PipelineCase, Dr2GivesSmallerNeighbourSizeRatiosThanDr8) {
  const Mesh dr2 = meshCase(exampleCase("fig7_rect_holes_dr2"));
  const Mesh dr8 = meshCase(exampleCase("fig7_rect_holes_dr8"));
  const Mesh none = meshCase(exampleCase("fig6_rect_holes_nosmooth"));
  const double r2 = largestNeighbourSizeRatio(dr2), r8 = largestNeighbourSizeRatio(dr8),
               r0 = largestNeighbourSizeRatio(none);
  std::cout << "[ figures  ] largest neighbour size ratio: dr 2 " << r2 << ", dr 8 " << r8 << ", none " << r0 << "\n";
  EXPECT_LT(r2, r8);
  EXPECT_LT(r8, r0);
}

TEST(PipelineCase, NarrowChannelIsRefinedInTheGap) {
  const CaseSpec spec = narrowChannel();
  PipelineReport report;
  std::unique_ptr<AdaptiveControlSpace> cs;
  const Mesh mesh = meshCase(spec, &report, {}, &cs);
  EXPECT_TRUE(report.updatesConverged);
  EXPECT_GT(report.proximitySources, 0);
  // Boundary points of both holes near the gap (at x = 2).
  int left = 0, right = 0;
  for (const Vec3& p : mesh.points) {
    if ((p.head<2>() - Vec2(2, 1)).norm() > 0.1) continue;
    if (std::abs((p.head<2>() - Vec2(1.49, 1)).norm() - 0.5) < 1e-9) ++left;
    if (std::abs((p.head<2>() - Vec2(2.51, 1)).norm() - 0.5) < 1e-9) ++right;
  }
  EXPECT_GE(left, 4);
  EXPECT_GE(right, 4);
  const QualityReport q = measureQuality(mesh, *cs);
  EXPECT_EQ(q.inverted, 0);
  EXPECT_EQ(q.degenerate, 0);
  // No element spanning the gap (vertices on both holes) has a bad metric quality.
  const std::vector<double> quality = elementQualities(mesh, *cs);
  auto onHole = [&](int v, double cx) {
    return std::abs((mesh.points[v].head<2>() - Vec2(cx, 1)).norm() - 0.5) < 1e-9;
  };
  int spanning = 0;
  double worst = 1.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    bool l = false, r = false;
    for (int v : mesh.triangles[t]) l = l || onHole(v, 1.49), r = r || onHole(v, 2.51);
    if (!(l && r)) continue;
    ++spanning;
    worst = std::min(worst, quality[t]);
  }
  std::cout << "[ figures  ] narrow channel: " << report.updateRounds << " rounds, " << left << " + " << right
            << " boundary points near the gap, " << spanning << " triangles across it, worst Q " << worst << "\n";
  EXPECT_GE(worst, 0.3);
  // Without the updates the gap is crossed by elements of poor metric quality.
  BoundaryUpdateOptions off;
  off.enabled = false;
  std::unique_ptr<AdaptiveControlSpace> cs0;
  const Mesh coarse = meshCase(spec, nullptr, off, &cs0);
  EXPECT_LT(coarse.points.size(), mesh.points.size());
}

TEST(PipelineCase, CoarseCircleChordsWithinTolerance) {
  const CaseSpec spec = coarseCircle();
  BoundaryUpdateOptions off;
  off.enabled = false;
  const double before = circleChordDeviation(meshCase(spec, nullptr, off), 2, {0, 0}, 1.0);
  PipelineReport report;
  const BoundaryUpdateOptions on;
  const Mesh mesh = meshCase(spec, &report, on);
  const double after = circleChordDeviation(mesh, 2, {0, 0}, 1.0);
  std::cout << "[ figures  ] coarse circle: chord deviation / chord " << before << " -> " << after << " in "
            << report.updateRounds << " rounds\n";
  EXPECT_GT(before, on.chordTolerance);
  EXPECT_LE(after, on.chordTolerance);
  EXPECT_GT(report.chordSources, 0);
  EXPECT_TRUE(report.updatesConverged);
}

TEST(PipelineCase, ShortSegmentsRefineTheStructureNearThem) {
  // The bottom side has metric length 1.5: two segments of 0.75 < eps1.
  const CaseSpec spec = parseCaseJson(R"({
    "domain": {"outer": [{"type": "polyline", "points": [[0, 0], [0.15, 0], [0.15, 1], [0, 1], [0, 0]]}]},
    "controlSpace": {"hmax": 0.1}})");
  PipelineReport report;
  const Mesh mesh = meshCase(spec, &report);
  EXPECT_GT(report.shortSegments, 0);
  EXPECT_GT(report.refinedElements, 0);
  EXPECT_TRUE(report.updatesConverged);
  // Round 2 measures the kept bottom segments in the updated metric (their own length
  // requested along them): nothing more to do.
  EXPECT_EQ(report.updateRounds, 2);
  EXPECT_GT(mesh.triangles.size(), 10u);
}

TEST(PipelineCase, UpdateLoopTerminatesAndIsDeterministic) {
  PipelineReport a, b;
  const Mesh m1 = meshCase(narrowChannel(), &a);
  const Mesh m2 = meshCase(narrowChannel(), &b);
  expectSameCaseMesh(m1, m2);
  EXPECT_EQ(a.updateRounds, b.updateRounds);
  EXPECT_LE(a.updateRounds, BoundaryUpdateOptions().maxRounds);
  // A round limit stops the loop and says so.
  BoundaryUpdateOptions one;
  one.maxRounds = 1;
  PipelineReport c;
  meshCase(narrowChannel(), &c, one);
  EXPECT_FALSE(c.updatesConverged);
  EXPECT_FALSE(c.notes.empty());
}

TEST(PipelineRemesh, HgradSmoothsTheBackgroundMeshControlSpace) {
  // A 4x4 grid of the unit square, fine at one corner vertex.
  Mesh m;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) m.points.push_back(Vec3(0.25 * i, 0.25 * j, 0));
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i;
      m.triangles.push_back({a, a + 1, a + 6});
      m.triangles.push_back({a, a + 6, a + 5});
    }
  std::vector<Metric> metrics(m.points.size(), Metric::isotropic(0.2));
  metrics[12] = Metric::isotropic(0.005);  // the centre (0.5, 0.5)
  RemeshOptions sharp, graded;
  graded.hgrad = 1.5;
  const auto cs0 = buildRemeshControlSpace(m, metrics, sharp);
  const auto cs1 = buildRemeshControlSpace(m, metrics, graded);
  EXPECT_STREQ(cs1->kindName(), "background");
  EXPECT_TRUE(cs1->metricAt({0.5, 0.5}).sizeAlong({1, 0}) < 0.006);
  const double a = gradationSlope(1.5);
  // Linear Mt between the centre and its neighbour 0.25 away makes h jump near the
  // neighbour (0.2 there): the smoothing bounds it by the slope.
  for (double d : {0.24, 0.25}) {
    const double h = cs1->metricAt({0.5 + d, 0.5}).sizeAlong({1, 0});
    EXPECT_LE(h, 0.005 + 1.05 * a * d + 0.01) << d;
    EXPECT_LT(h, cs0->metricAt({0.5 + d, 0.5}).sizeAlong({1, 0})) << d;
  }
  const Mesh out = remesh(m, metrics, graded);
  EXPECT_GT(out.triangles.size(), 50u);
  // The NodeSource insertion builds the same kind of structure.
  RemeshOptions nodes = graded;
  nodes.insertion = RemeshMetricInsertion::NodeSource;
  const auto cs2 = buildRemeshControlSpace(m, metrics, nodes);
  EXPECT_STREQ(cs2->kindName(), "background");
  EXPECT_LE(cs2->metricAt({0.75, 0.5}).sizeAlong({1, 0}), 0.005 + 1.05 * a * 0.25 + 0.01);
  EXPECT_THROW(buildRemeshControlSpace(m, std::vector<Metric>(3), graded), Error);
}

// remesh(Mesh&&, ...) frees its input once the control space is built: the same mesh.
TEST(PipelineRemesh, MovedInputGivesTheSameMesh) {
  Mesh m;
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i <= 6; ++i) m.points.push_back(Vec3(i / 6.0, j / 6.0, 0));
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      const int a = j * 7 + i;
      m.triangles.push_back({a, a + 1, a + 8});
      m.triangles.push_back({a, a + 8, a + 7});
    }
  std::vector<Metric> metrics;
  for (const Vec3& p : m.points) metrics.push_back(Metric::fromSizes(0.3, 0.01 + 0.2 * std::abs(p.y() - 0.5), 0.1));
  RemeshOptions o;
  o.hgrad = 1.5;
  PipelineReport r0, r1;
  const Mesh kept = remesh(m, metrics, o, &r0);
  Mesh copy = m;
  std::vector<Metric> metricsCopy = metrics;
  const Mesh moved = remesh(std::move(copy), std::move(metricsCopy), o, &r1);
  EXPECT_GT(kept.triangles.size(), 100u);
  EXPECT_EQ(moved.points, kept.points);
  EXPECT_EQ(moved.triangles, kept.triangles);
  EXPECT_EQ(moved.edges, kept.edges);
  EXPECT_EQ(moved.edgeRefs, kept.edgeRefs);
  EXPECT_EQ(r1.controlNodes, r0.controlNodes);
  EXPECT_EQ(r1.boundaryPoints, r0.boundaryPoints);
}

TEST(PipelineStats, NeighbourSizeRatioAndStatsJson) {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(4, 4, 0)};
  m.triangles = {{0, 1, 2}, {1, 3, 2}};
  // Areas 0.5 and 3.5: ratio sqrt(7).
  EXPECT_NEAR(largestNeighbourSizeRatio(m), std::sqrt(7.0), 1e-12);
  const UniformControlSpace cs({{0, 0}, {4, 4}}, Metric::isotropic(1));
  PipelineReport r;
  r.updateRounds = 3;
  const auto j = pipelineStatsJson(m, cs, r);
  EXPECT_EQ(j["triangles"], 2);
  EXPECT_EQ(j["boundaryUpdates"]["rounds"], 3);
  EXPECT_NEAR(j["largestNeighbourSizeRatio"].get<double>(), std::sqrt(7.0), 1e-12);
  EXPECT_TRUE(j.contains("pipelineSeconds"));
  EXPECT_TRUE(j.contains("edgeLength"));
  const auto q = elementQualities(m, cs);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_GT(q[0], 0.5);
}

// The paper's section 3.2 rules on planar boundaries, each pinned by the figure the paper
// gives: eps1 = 0.8 with the segment's length as the reference size, the [1/2, 2]
// invalidation (and re-discretization of invalid contours only), the chord deviation
// check with curvature sources h2 = dMax h1 across the contour, and the eps2 = 0.2
// proximity test on metric areas. Expected values are computed here from the rules.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "anisomesh/boundary/boundary_updates.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/pipeline/pipeline.h"

using namespace anisomesh;

namespace {

Box2 box() { return Box2{Vec2(-10.0, -10.0), Vec2(10.0, 10.0)}; }

// A closed loop through the given points (segment i joins points i and i + 1).
BoundaryLoop loopOf(const std::vector<Vec2>& pts) {
  BoundaryLoop l;
  l.points = pts;
  l.edgeRefs.assign(pts.size(), 1);
  return l;
}

// A triangle-shaped loop whose first segment has length a and lies on y = y0.
BoundaryLoop withFirstSegment(double a, double y0) { return loopOf({{0.0, y0}, {a, y0}, {0.5 * a, y0 + 1.0}}); }

}  // namespace

// The paper's thresholds are the defaults.
TEST(PaperRulesBoundary, DefaultsAreThePapersValues) {
  const BoundaryUpdateOptions o;
  EXPECT_EQ(o.eps1, 0.8);
  EXPECT_EQ(o.lengthMin, 0.5);
  EXPECT_EQ(o.lengthMax, 2.0);
  EXPECT_EQ(o.eps2, 0.2);
}

// eps1: segments of metric length below 0.8 are short; the update is a source along the
// segment whose metric asks for the segment's own length (the reference size): the metric
// at its middle with every size times the metric length, within the segment's length.
TEST(PaperRulesBoundary, Eps1UsesTheSegmentLengthAsReference) {
  const UniformControlSpace cs(box(), Metric::fromSizes(0.0, 2.0, 0.5));  // 2 along x, 0.5 along y
  // First segments along x of Euclidean length 1.58 / 1.62: metric length 0.79 / 0.81.
  const std::vector<BoundaryLoop> loops = {withFirstSegment(1.58, 0.0), withFirstSegment(1.62, 5.0)};
  const SegmentLengthCheck c = checkSegmentLengths(loops, cs, {});
  ASSERT_EQ(c.shortSegments.size(), 1u);
  EXPECT_EQ(c.shortSegments[0].contour, 0);
  EXPECT_NEAR(c.shortSegments[0].length, 0.79, 1e-12);
  std::vector<MetricSource> sources;
  ASSERT_EQ(shortSegmentSources(c.shortSegments, cs, 0.0, &sources), 1);
  const auto& s = std::get<SegmentSource>(sources[0]);
  EXPECT_EQ(s.a, Vec2(0.0, 0.0));
  EXPECT_EQ(s.b, Vec2(1.58, 0.0));
  EXPECT_NEAR(s.radius, 1.58, 1e-12);
  // Size along the segment = its Euclidean length (metric length 1), across scaled alike.
  EXPECT_NEAR(s.metric.sizeAlong({1.0, 0.0}), 1.58, 1e-12);
  EXPECT_NEAR(s.metric.sizeAlong({0.0, 1.0}), 0.5 * 0.79, 1e-12);
  // A lower clamp that undoes the update: no source (the loop would never end).
  std::vector<MetricSource> none;
  EXPECT_EQ(shortSegmentSources(c.shortSegments, cs, 10.0, &none), 0);
}

// The whole run: a strip 0.15 wide in a size of 0.1 has bottom segments of metric length
// 0.75 < eps1; afterwards the control space asks for their length (0.075) along them.
TEST(PaperRulesBoundary, Eps1UpdateReachesTheFinalControlSpace) {
  const CaseSpec spec = parseCaseJson(R"({
    "domain": {"outer": [{"type": "polyline", "points": [[0, 0], [0.15, 0], [0.15, 1], [0, 1], [0, 0]]}]},
    "controlSpace": {"hmax": 0.1}})");
  PipelineReport report;
  std::unique_ptr<AdaptiveControlSpace> cs;
  const Mesh mesh = meshCase(spec, &report, {}, &cs);
  EXPECT_GT(report.shortSegments, 0);
  EXPECT_GT(report.shortSegmentSources, 0);
  EXPECT_TRUE(report.updatesConverged);
  for (double x : {0.0375, 0.1125}) EXPECT_NEAR(cs->metricAt({x, 0.0}).sizeAlong({1.0, 0.0}), 0.075, 0.0075) << x;
  // Far from the strip's ends the size is the case's.
  EXPECT_NEAR(cs->metricAt({0.075, 0.5}).sizeAlong({0.0, 1.0}), 0.1, 1e-9);
  EXPECT_GT(mesh.triangles.size(), 10u);
}

// [1/2, 2]: a segment of metric length below 1/2 or above 2 makes its contour invalid.
TEST(PaperRulesBoundary, SegmentsOutsideHalfToTwoInvalidateTheirContour) {
  const UniformControlSpace cs(box(), Metric::isotropic(1.0));
  const std::vector<BoundaryLoop> loops = {loopOf({{0, 0}, {1, 0}, {1, 1}, {0, 1}}),         // 1, 1, 1, 1
                                           withFirstSegment(0.49, 2.0),                      // 0.49
                                           withFirstSegment(0.51, 4.0),                      // 0.51
                                           loopOf({{0, 6}, {2.01, 6}, {2.01, 7}, {0, 7}}),   // 2.01
                                           loopOf({{0, 8}, {1.99, 8}, {1.99, 9}, {0, 9}})};  // 1.99
  const SegmentLengthCheck c = checkSegmentLengths(loops, cs, {});
  EXPECT_EQ(c.invalidContours, (std::vector<char>{0, 1, 0, 1, 0}));
  EXPECT_EQ(c.invalidSegments, 3);  // 0.49, and 2.01 twice (the top side too)
}

// Only invalid contours are discretized again; a kept contour that would cross a fresh
// one is replaced too.
TEST(PaperRulesBoundary, OnlyInvalidContoursAreRediscretized) {
  const std::vector<BoundaryLoop> old = {loopOf({{0, 0}, {4, 0}, {4, 4}, {0, 4}}), loopOf({{1, 1}, {1, 2}, {2, 2}}),
                                         loopOf({{3, 1}, {3, 2}, {3.5, 2}})};
  std::vector<BoundaryLoop> fresh = {loopOf({{0, 0}, {2, 0}, {4, 0}, {4, 4}, {0, 4}}),
                                     loopOf({{1, 1}, {1, 1.5}, {1, 2}, {2, 2}}),
                                     loopOf({{3, 1}, {3, 1.5}, {3, 2}, {3.5, 2}})};
  std::vector<BoundaryLoop> loops = old;
  EXPECT_EQ(keepValidContours(loops, fresh, {0, 1, 0}), (std::vector<char>{0, 1, 0}));
  EXPECT_EQ(loops[0].points, old[0].points);
  EXPECT_EQ(loops[1].points, fresh[1].points);
  EXPECT_EQ(loops[2].points, old[2].points);
  // The fresh hole 1 reaches into the kept hole 2: hole 2 is replaced as well.
  fresh[1] = loopOf({{1, 1}, {1, 2}, {3.2, 1.5}});
  fresh[2] = loopOf({{3.3, 1}, {3.3, 2}, {3.5, 2}});
  loops = old;
  EXPECT_EQ(keepValidContours(loops, fresh, {0, 1, 0}), (std::vector<char>{0, 1, 1}));
  EXPECT_EQ(loops[2].points, fresh[2].points);
}

// The whole run: after proximity updates the two holes' segments near the gap would be far
// longer than 2 in the refined metric; being invalid they are discretized again, so every
// boundary segment of the final mesh has metric length in [1/2, 2] in the final space.
// Square holes: no chord check, only the length rule makes them invalid.
TEST(PaperRulesBoundary, FinalBoundarySegmentsLieInHalfToTwo) {
  const char* holes[] = {
      R"([[{"type": "circle", "center": [1.49, 1], "radius": 0.5, "ref": 2}],
          [{"type": "circle", "center": [2.51, 1], "radius": 0.5, "ref": 3}]])",
      R"([[{"type": "polyline", "points": [[0.49, 0.5], [1.49, 0.5], [1.49, 1.5], [0.49, 1.5], [0.49, 0.5]]}],
          [{"type": "polyline", "points": [[1.51, 0.5], [2.51, 0.5], [2.51, 1.5], [1.51, 1.5], [1.51, 0.5]]}]])"};
  for (const char* h : holes) {
    const CaseSpec spec = parseCaseJson(std::string(R"({"domain": {"outer": [{"type": "polyline",
      "points": [[0, 0], [4, 0], [4, 2], [0, 2], [0, 0]], "ref": 1}], "holes": )") +
                                        h + R"(}, "controlSpace": {"hmin": 0.001, "hmax": 0.5, "gradation": 2}})");
    PipelineReport report;
    std::unique_ptr<AdaptiveControlSpace> cs;
    const Mesh mesh = meshCase(spec, &report, {}, &cs);
    EXPECT_TRUE(report.updatesConverged);
    EXPECT_GT(report.proximitySources, 0);
    EXPECT_GT(report.rediscretizedContours, 0);
    double lo = 1e300, hi = 0.0;
    for (const auto& e : mesh.edges) {
      const double l = segmentMetricLength(*cs, mesh.points[e[0]].head<2>(), mesh.points[e[1]].head<2>());
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
    EXPECT_GE(lo, 0.5) << h;
    EXPECT_LE(hi, 2.0) << h;
  }
}

// Chord deviation: a circle of radius 1 in a uniform size 1 has 6 chords deviating by
// (1 - cos 30 deg) / 1 = 0.134 from it; above chordTolerance = 0.05 the contour is invalid
// and curvature sources follow it, with h1 = 0.75 * 8 R tol along the tangent and
// h2 = dMax h1 across (dMax = 4 and 2).
TEST(PaperRulesBoundary, ChordDeviationAddsCurvatureSourcesWithDmax) {
  const CaseSpec spec = parseCaseJson(R"({
    "domain": {"outer": [{"type": "polyline", "points": [[-2, -2], [2, -2], [2, 2], [-2, 2], [-2, -2]]}],
               "holes": [[{"type": "circle", "center": [0, 0], "radius": 1}]]},
    "controlSpace": {"hmax": 1.0}})");
  const UniformControlSpace cs(box(), Metric::isotropic(1.0));
  for (double dMax : {4.0, 2.0}) {
    BoundaryUpdateOptions o;
    o.dMax = dMax;
    std::vector<MetricSource> sources;
    std::vector<char> invalid(2, 0);
    const double worst = chordSources(spec.domain, cs, o, &sources, &invalid);
    EXPECT_NEAR(worst, 1.0 - std::sqrt(3.0) / 2.0, 1e-6);
    EXPECT_EQ(invalid, (std::vector<char>{0, 1}));
    ASSERT_EQ(sources.size(), 6u * 8u);
    const double h1 = 0.75 * 8.0 * 1.0 * o.chordTolerance;
    for (const MetricSource& m : sources) {
      const auto& s = std::get<SegmentSource>(m);
      const Vec2 t = (s.b - s.a).normalized(), n(-t.y(), t.x());
      EXPECT_NEAR(s.metric.sizeAlong(t), h1, 1e-3 * h1);
      EXPECT_NEAR(s.metric.sizeAlong(n), dMax * h1, 1e-3 * h1);
    }
    // Within tolerance: nothing.
    o.chordTolerance = 0.14;
    std::vector<MetricSource> none;
    std::vector<char> valid(2, 0);
    chordSources(spec.domain, cs, o, &none, &valid);
    EXPECT_TRUE(none.empty());
    EXPECT_EQ(valid, (std::vector<char>{0, 0}));
  }
}

// eps2: a boundary triangle joining two loops is a gap when its metric area (area times
// det Mt) is below eps2 sqrt(3)/4; the source across it asks for width / gapElements.
TEST(PaperRulesBoundary, Eps2ComparesMetricAreas) {
  for (double h : {1.0, 2.0}) {
    // Metric area g / (2 h^2) against 0.2 sqrt(3)/4 = 0.0866: the threshold gap is 0.1732 h^2.
    for (double g : {0.17 * h * h, 0.18 * h * h}) {
      const std::vector<BoundaryLoop> loops = {loopOf({{0, 0}, {1, 0}, {1, 1}, {0, 1}}),
                                               loopOf({{1 + g, 0}, {1 + g, 1}, {2 + g, 1}, {2 + g, 0}})};
      Mesh m;
      for (const BoundaryLoop& l : loops)
        for (const Vec2& p : l.points) m.points.push_back(Vec3(p.x(), p.y(), 0.0));
      m.triangles.push_back({1, 4, 2});  // (1,0) (1+g,0) (1,1): area g / 2
      const UniformControlSpace cs(box(), Metric::isotropic(h));
      std::vector<MetricSource> sources;
      const int added = proximitySources(loops, m, cs, {}, &sources);
      if (g < 0.1732 * h * h) {
        ASSERT_EQ(added, 1) << h << " " << g;
        const auto& s = std::get<RadialSource>(sources[0]);
        const double width = g / std::sqrt(1.0 + g * g);  // height across the longest edge
        EXPECT_NEAR(s.metric.sizeAlong({1.0, 0.0}), width / 2.0, 1e-12);
      } else {
        EXPECT_EQ(added, 0) << h << " " << g;
      }
    }
  }
}

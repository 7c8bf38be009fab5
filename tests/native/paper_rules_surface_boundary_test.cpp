// The section 3.2 rules on surface patches are those of planar cases (boundary_updates.h):
// each threshold of SurfaceMeshOptions::boundary is the one the surface mesher applies, so
// hard-coding a value again (or dropping a rule) fails one of these tests. Cases: plane
// patches (the parameterization is the identity, so metric lengths are plain lengths over
// the requested size) and the sphere band with the contour curvature left out of the
// initial control space (so only the section 3.2 chord check sizes its boundary).
#include <gtest/gtest.h>

#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/pipeline/pipeline.h"

using namespace anisomesh;

namespace {

// A unit plane patch with the given holes (JSON contours) and boundary rules, hmax = h.
SurfaceCaseSpec planeCase(const std::string& holes, double h, const std::string& boundary = "{}") {
  return parseSurfaceCaseJson(R"({"metric": {"chordTolerance": 0.01, "hmin": 0.0005, "hmax": )" + std::to_string(h) +
                              R"(, "gradation": 2.0}, "boundary": )" + boundary +
                              R"(, "patches": [{"name": "plate", "surface": {"type": "plane"}, "holes": )" + holes +
                              "}]}");
}

// A hole far smaller than the size: its circle gets three segments (the minimum) of metric
// length about 0.09, below eps1 = 0.8.
const char* kTinyHole = R"([[{"type": "circle", "center": [0.5, 0.5], "radius": 0.01}]])";
// Two slots 0.01 apart, with sizes 0.1: the boundary triangles across the gap have a metric
// area far below eps2 = 0.2 (unit triangle: sqrt3 / 4).
const char* kTwoSlots =
    R"([[{"type": "polyline", "points": [[0.3, 0.3], [0.445, 0.3], [0.445, 0.7], [0.3, 0.7], [0.3, 0.3]]}],
        [{"type": "polyline", "points": [[0.455, 0.3], [0.6, 0.3], [0.6, 0.7], [0.455, 0.7], [0.455, 0.3]]}]])";

SurfaceMeshReport runBoundaryCase(const SurfaceCaseSpec& spec, Mesh* mesh = nullptr) {
  SurfaceMeshReport r;
  const Mesh m = meshSurfaceCase(spec, &r);
  if (mesh) *mesh = m;
  return r;
}

int trianglesNear(const Mesh& m, const Vec2& c, double radius) {
  int n = 0;
  for (const auto& t : m.triangles) {
    const Vec3 g = (m.points[size_t(t[0])] + m.points[size_t(t[1])] + m.points[size_t(t[2])]) / 3.0;
    if ((g.head<2>() - c).norm() < radius) ++n;
  }
  return n;
}

}  // namespace

// eps1: segments shorter than eps1 update the control space along them (with the
// segment's length as the reference size, shortSegmentSources); below the threshold no update.
TEST(PaperRulesSurfaceBoundary, Eps1IsTheThresholdOfShortSegments) {
  Mesh withUpdates, without;
  const SurfaceMeshReport def = runBoundaryCase(planeCase(kTinyHole, 0.2), &withUpdates);
  const SurfaceMeshReport low = runBoundaryCase(planeCase(kTinyHole, 0.2, R"({"eps1": 0.05})"), &without);
  EXPECT_GT(def.shortSegmentSources, 0);
  EXPECT_EQ(low.shortSegmentSources, 0);
  // The updates grade the mesh down to the hole: more triangles near it.
  EXPECT_GT(trianglesNear(withUpdates, Vec2(0.5, 0.5), 0.1), trianglesNear(without, Vec2(0.5, 0.5), 0.1));
}

// eps2: boundary triangles of metric area below eps2 sqrt3/4 joining non-adjacent boundary
// pieces put a radial source over the gap; with eps2 tiny there is none.
TEST(PaperRulesSurfaceBoundary, Eps2IsTheProximityThreshold) {
  Mesh withUpdates, without;
  const SurfaceMeshReport def = runBoundaryCase(planeCase(kTwoSlots, 0.1), &withUpdates);
  const SurfaceMeshReport off = runBoundaryCase(planeCase(kTwoSlots, 0.1, R"({"eps2": 1e-9})"), &without);
  EXPECT_GT(def.proximitySources, 0);
  EXPECT_EQ(off.proximitySources, 0);
  EXPECT_GT(trianglesNear(withUpdates, Vec2(0.45, 0.5), 0.02), trianglesNear(without, Vec2(0.45, 0.5), 0.02));
}

// [lengthMin, lengthMax]: once the gap's sources refine the control space, the slots'
// segments along the gap measure more than lengthMax = 2 there, so their contours are
// invalidated and discretized again; with lengthMax out of reach they never are.
TEST(PaperRulesSurfaceBoundary, SegmentsAboveLengthMaxInvalidateTheirContour) {
  const SurfaceMeshReport def = runBoundaryCase(planeCase(kTwoSlots, 0.1));
  const SurfaceMeshReport wide = runBoundaryCase(planeCase(kTwoSlots, 0.1, R"({"lengthMax": 1e9})"));
  EXPECT_GT(def.invalidations, 0);
  EXPECT_GT(def.rounds, 1);
  EXPECT_EQ(wide.invalidations, 0);
}

// The chord check (in 3D, against metric.chordTolerance): with contourCurvature off the
// sphere band's boundary circles are sized by it alone, so it adds segment sources and
// invalidates the circles, which are discretized again until their chords are within it.
TEST(PaperRulesSurfaceBoundary, ChordCheckInvalidatesCurvedContours) {
  const SurfaceMeshReport r = runBoundaryCase(parseSurfaceCaseJson(
      R"({"metric": {"chordTolerance": 0.004, "hmin": 0.01, "hmax": 0.5, "maxAspectRatio": 5, "gradation": 2.0,
                     "contourCurvature": false},
          "patches": [{"name": "band", "surface": {"type": "sphere", "radius": 1.0,
                       "domain": [[0, -1.2], [6.283185307179586, 1.2]]}}],
          "shared": [{"a": {"patch": "band", "contour": 0, "curve": 1},
                      "b": {"patch": "band", "contour": 0, "curve": 3}}]})"));
  EXPECT_GT(r.chordSources, 0);
  EXPECT_GT(r.invalidations, 0);
  EXPECT_GT(r.rounds, 1);
}

// dMax (h2 = dMax h1 across a contour): the chord sources of a circular hole in a plane patch
// (contourCurvature off, so only they size the boundary; hmax far above them) are dMax times
// longer across the circle than along it. With dMax = 1 they are round, so the ring of
// triangles along the hole is finer across it: more triangles there than with the default 4.
TEST(PaperRulesSurfaceBoundary, DMaxScalesTheSizeAcrossTheContour) {
  auto ringCase = [](const std::string& dMax) {
    return parseSurfaceCaseJson(
        R"({"metric": {"chordTolerance": 0.0005, "hmin": 0.0005, "hmax": 0.3, "gradation": 2.0,
                       "contourCurvature": false}, "boundary": {"dMax": )" +
        dMax + R"(}, "patches": [{"name": "plate", "surface": {"type": "plane"},
                  "holes": [[{"type": "circle", "center": [0.5, 0.5], "radius": 0.2}]]}]})");
  };
  Mesh round, stretched;
  const SurfaceMeshReport r1 = runBoundaryCase(ringCase("1"), &round);
  const SurfaceMeshReport r4 = runBoundaryCase(ringCase("4"), &stretched);
  EXPECT_GT(r1.chordSources, 0);
  EXPECT_GT(r4.chordSources, 0);
  auto ring = [](const Mesh& m) {  // triangles with their centroid within 0.04 of the circle
    int n = 0;
    for (const auto& t : m.triangles) {
      const Vec3 g = (m.points[size_t(t[0])] + m.points[size_t(t[1])] + m.points[size_t(t[2])]) / 3.0;
      const double r = (g.head<2>() - Vec2(0.5, 0.5)).norm();
      if (r > 0.2 && r < 0.24) ++n;
    }
    return n;
  };
  EXPECT_GT(ring(round), 1.5 * ring(stretched));
}

// The surface format's "boundary" section is read by the planar reader's rules.
TEST(PaperRulesSurfaceBoundary, BoundarySectionIsCheckedLikeThePlanarOne) {
  EXPECT_THROW(planeCase(kTinyHole, 0.2, R"({"lengthMax": 0.9})"), Error);
  EXPECT_THROW(planeCase(kTinyHole, 0.2, R"({"chordTolerance": 0.1})"), Error);  // planar only
  EXPECT_THROW(planeCase(kTinyHole, 0.2, R"({"eps1": -1})"), Error);
  EXPECT_THROW(planeCase(kTinyHole, 0.2, R"({"eps1": 1.5})"), Error);  // unit segments would be short
  const SurfaceCaseSpec s = planeCase(kTinyHole, 0.2, R"({"eps1": 0.7, "eps2": 0.3, "dMax": 3})");
  EXPECT_EQ(s.options.boundary.eps1, 0.7);
  EXPECT_EQ(s.options.boundary.eps2, 0.3);
  EXPECT_EQ(s.options.boundary.dMax, 3.0);
}

// MMG's -hausd, -ar and -nr for remesh: the boundary between corners reconstructed as a C1
// spline through the input's boundary vertices and re-discretized within the Hausdorff
// distance H of it; corners where the boundary turns by more than the ridge angle (or
// only at reference changes with -nr).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/curve.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/pipeline/remesh_geometry.h"
#include "cli_test_util.h"

using namespace anisomesh;

namespace {

constexpr double kPiHausdorff = 3.141592653589793;

// A disk of radius 1: n boundary vertices, a fan from the centre.
Mesh diskMesh(int n) {
  Mesh m;
  m.points.push_back(Vec3::Zero());
  for (int k = 0; k < n; ++k)
    m.points.push_back(Vec3(std::cos(2 * kPiHausdorff * k / n), std::sin(2 * kPiHausdorff * k / n), 0));
  for (int k = 0; k < n; ++k) {
    m.triangles.push_back({0, 1 + k, 1 + (k + 1) % n});
    m.triangleRefs.push_back(1);
  }
  m.pointRefs.assign(m.points.size(), 0);
  return m;
}

// The unit square's boundary, points every 0.05, with a zigzag of amplitude 0.008 on
// the bottom side (turns of about 35 degrees); refs 1-4 per side when perSideRefs.
BoundaryLoop noisySquare(bool perSideRefs) {
  BoundaryLoop l;
  const Vec2 corners[4] = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  for (int s = 0; s < 4; ++s)
    for (int k = 0; k < 20; ++k) {
      Vec2 p = corners[s] + (corners[(s + 1) % 4] - corners[s]) * (k / 20.0);
      if (s == 0 && k >= 6 && k <= 12) p.y() += (k % 2 ? 0.008 : -0.008);
      l.points.push_back(p);
      l.edgeRefs.push_back(perSideRefs ? s + 1 : 7);
    }
  return l;
}

int countCurves(const BoundaryLoop& l, double angle) {
  LoopDomainOptions o;
  o.cornerAngle = angle;
  o.smooth = true;
  return int(domainFromBoundaryLoops({l}, o).outer.curves.size());
}

// Distance of p from the curve: dense samples, then golden-section refinement.
double distanceToCurve(const Curve& c, const Vec2& p) {
  const int n = 4000;
  int best = 0;
  for (int k = 1; k <= n; ++k)
    if ((c.point(double(k) / n) - p).norm() < (c.point(double(best) / n) - p).norm()) best = k;
  double a = std::max(0.0, (best - 1.0) / n), b = std::min(1.0, (best + 1.0) / n);
  for (int it = 0; it < 100; ++it) {
    const double m1 = a + (b - a) * 0.382, m2 = a + (b - a) * 0.618;
    if ((c.point(m1) - p).norm() < (c.point(m2) - p).norm())
      b = m2;
    else
      a = m1;
  }
  return (c.point(0.5 * (a + b)) - p).norm();
}

}  // namespace

TEST(RemeshHausdorff, SplineInterpolatesJoinsC1AndFollowsACircle) {
  const int n = 32;
  std::vector<Vec2> pts;
  for (int k = 0; k <= n / 2; ++k)
    pts.push_back(Vec2(std::cos(2 * kPiHausdorff * k / n), std::sin(2 * kPiHausdorff * k / n)));
  const SplineCurve c(pts);
  const double sagitta = 1 - std::cos(kPiHausdorff / n);  // the polygon's chord error
  double worst = 0, kink = 0;
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    const double t0 = double(i) / double(pts.size() - 1);
    EXPECT_LT((c.point(t0) - pts[i]).norm(), 1e-12) << i;  // chord length = uniform here
    for (int k = 1; k < 10; ++k)
      worst = std::max(worst, std::abs(c.point(t0 + k / (10.0 * (pts.size() - 1))).norm() - 1));
    if (i > 0) {
      const Vec2 left = c.derivative(t0 - 1e-9), right = c.derivative(t0 + 1e-9);
      kink = std::max(kink, (left - right).norm() / right.norm());
    }
  }
  EXPECT_LT(worst, sagitta / 50) << "the spline follows the circle far closer than the polygon";
  EXPECT_LT(kink, 1e-6) << "C1 at the interior vertices";
  // Joined pieces of a split smooth loop share their tangent direction.
  const Vec2 before = pts[pts.size() - 2],
             after = Vec2(std::cos(2 * kPiHausdorff * 17 / n), std::sin(2 * kPiHausdorff * 17 / n));
  const std::vector<Vec2> second{pts.back(), after,
                                 Vec2(std::cos(2 * kPiHausdorff * 18 / n), std::sin(2 * kPiHausdorff * 18 / n))};
  const SplineCurve a(pts, 0, nullptr, &after), b(second, 0, &before, nullptr);
  const Vec2 ta = a.derivative(1.0).normalized(), tb = b.derivative(0.0).normalized();
  EXPECT_LT((ta - tb).norm(), 1e-12);
  EXPECT_THROW(SplineCurve({Vec2(0, 0)}), Error);
}

// A 64-gon disk remeshed coarser (h = 0.3 against edges of 0.098) with -hausd 0.002: the new
// boundary vertices lie on the spline through the input's vertices, every chord is within
// H of it, and they lie on the true circle far closer than the input polygon's chord error
// (where the polyline boundary of a run without -hausd puts them).
TEST(RemeshHausdorff, CoarserCircleKeepsItsBoundaryWithinH) {
  const Mesh in = diskMesh(64);
  const double H = 0.002, inputSagitta = 1 - std::cos(kPiHausdorff / 64);
  const std::vector<Metric> metrics(in.points.size(), Metric::isotropic(0.3));
  RemeshOptions o;
  o.hausdorff = H;
  PipelineReport report;
  const Mesh out = remesh(in, metrics, o, &report);
  const Mesh polyline = remesh(in, metrics, RemeshOptions{});
  LoopDomainOptions lo;
  lo.smooth = true;
  lo.cornerAngle = kPiHausdorff / 4;
  const Domain domain = domainFromBoundaryLoops(boundaryLoopsFromMesh(in), lo);
  ASSERT_EQ(domain.outer.curves.size(), 3u) << "no corners: the loop split in three";

  double onCurve = 0, toCircle = 0, chord = 0;
  for (const auto& e : out.edges) {
    const Vec2 p = out.points[size_t(e[0])].head<2>(), q = out.points[size_t(e[1])].head<2>();
    double d = 1e300;
    for (const CurveUse& u : domain.outer.curves) d = std::min(d, distanceToCurve(*u.curve, p));
    onCurve = std::max(onCurve, d);
    toCircle = std::max(toCircle, std::abs(p.norm() - 1));
    const double half = 0.5 * (q - p).norm();
    chord = std::max(chord, 1 - std::sqrt(1 - half * half));  // the arc's distance from the chord
  }
  double polylineToCircle = 0;
  for (const auto& e : polyline.edges)
    polylineToCircle = std::max(polylineToCircle, std::abs(polyline.points[size_t(e[0])].head<2>().norm() - 1));
  EXPECT_LT(onCurve, 1e-9);
  EXPECT_LE(chord, H * 1.05) << "chords within H (the spline is the circle within 1e-5)";
  EXPECT_LT(toCircle, inputSagitta / 20);
  EXPECT_GT(polylineToCircle, inputSagitta / 4) << "without -hausd the vertices lie on the input polygon";
  EXPECT_GT(report.chordSources, 0);
  EXPECT_TRUE(report.updatesConverged);
  EXPECT_GT(out.edges.size(), polyline.edges.size()) << "H needs more boundary points than h = 0.3";
}

TEST(RemeshHausdorff, RidgeAngleFindsTheFourCornersOfANoisySquare) {
  const BoundaryLoop square = noisySquare(false);
  EXPECT_EQ(countCurves(square, kPiHausdorff / 4), 4) << "45 degrees: the 4 corners only";
  LoopDomainOptions o;
  o.cornerAngle = kPiHausdorff / 4;
  o.smooth = true;
  const Domain d = domainFromBoundaryLoops({square}, o);
  for (const CurveUse& u : d.outer.curves) {
    const Vec2 s = u.curve->start();
    EXPECT_TRUE((s.array() == 0 || s.array() == 1).all()) << formatPoint(s);
    EXPECT_STREQ(u.curve->typeName(), "spline");
  }
  EXPECT_GT(countCurves(square, 30 * kPiHausdorff / 180), 4) << "30 degrees: the zigzag's turns too";
  // -nr: no angle corners; reference changes stay corners.
  EXPECT_EQ(countCurves(square, kPiHausdorff), 3) << "one smooth loop, split in three";
  EXPECT_EQ(countCurves(noisySquare(true), kPiHausdorff), 4) << "the 4 reference changes";
}

// The CLI: -hausd, -ar, -nr accepted and checked; -hausd refines a coarse circle's boundary.
TEST(RemeshHausdorff, CliOptions) {
  const std::string in = clitest::tmp("disk.mesh"), out = clitest::tmp("out.mesh"), out2 = clitest::tmp("out2.mesh");
  writeMeditFile(in, diskMesh(64));
  ASSERT_EQ(clitest::run("remesh " + in + " -hsiz 0.3 -o " + out).code, 0);
  const clitest::CliRun r = clitest::run("remesh " + in + " -hsiz 0.3 -hausd 0.002 -ar 45 -o " + out2);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(readMeditFile(out2).edges.size(), readMeditFile(out).edges.size());
  EXPECT_EQ(clitest::run("remesh " + in + " -hsiz 0.3 -hausd 0.002 -nr -o " + out2).code, 0);
  for (const char* bad : {"-hausd 0", "-hausd -1", "-ar 200", "-ar 30 -nr", "-nr -ar 30", "-ar x"}) {
    const clitest::CliRun b = clitest::run("remesh " + in + " -hsiz 0.3 " + bad + " -o " + out2);
    EXPECT_EQ(b.code, 2) << bad << ": " << b.err;
  }
}

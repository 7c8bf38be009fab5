// A straight boundary crossing a strongly stretched layer obliquely: the metric Delaunay
// insertion leaves fans of slivers against such a boundary, and the swaps of the
// adaptation loop must be allowed to finish the chains of improving swaps that remove
// them (cut at 6 sweeps they left min Q 0.005-0.1; found on remesh_throughput.mjs's front
// case at 3e6 triangles, reproduced here on the planar mesher and on a piece of that case).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "anisomesh/pipeline/pipeline.h"
#include "mesh_test_util.h"

using namespace anisomesh;

namespace {

constexpr double kPi = 3.141592653589793;

// The curved front of remesh_throughput.mjs at 1e5 triangles (scale 10): size 0.01 along
// the front y = 0.5 + 0.1 sin(2 pi x), 0.00015 + 0.02 |d| across (aspect ratio up to 67);
// the front meets x = const at 32 degrees near x = 0.
struct Front {
  static constexpr double kScale = 10.0;
  static double f(double x) { return 0.1 * std::sin(2 * kPi * x); }
  static double df(double x) { return 0.2 * kPi * std::cos(2 * kPi * x); }
  static double hAlong() { return 0.1 / kScale; }
  static double hAcross(double d) { return std::min((0.0015 + 0.2 * std::abs(d)) / kScale, hAlong()); }
  static Metric metric(double x, double y) {
    const double g = std::hypot(df(x), 1.0);
    const double nx = -df(x) / g, ny = 1.0 / g;  // across the front
    const double a = 1.0 / std::pow(hAcross((y - 0.5 - f(x)) / g), 2), b = 1.0 / std::pow(hAlong(), 2);
    return Metric::fromTensor(a * nx * nx + b * ny * ny, (a - b) * nx * ny, a * ny * ny + b * nx * nx);
  }
};

// A carrier of the front's piece x in [0, 0.02], t in [t0, 0.56] (y = t + f(x)): columns
// every hAlong / 2, rows graded as the front's size across / 2 (the benchmark's carrier).
Mesh frontPiece(double t0, std::vector<Metric>* metrics) {
  std::vector<double> ss, ts;
  for (double s = 0.0; s <= 0.02 + 1e-12; s += Front::hAlong() / 2) ss.push_back(s);
  const double gmax = std::hypot(0.2 * kPi, 1.0);
  std::vector<double> half{0.5};
  for (double t = 0.5; t < 1.0;) {
    t += Front::hAcross(t - 0.5) / gmax / 2;
    half.push_back(std::min(t, 1.0));
  }
  for (auto it = half.rbegin(); it != half.rend() - 1; ++it) ts.push_back(1.0 - *it);
  ts.insert(ts.end(), half.begin(), half.end());
  ts.erase(std::remove_if(ts.begin(), ts.end(), [&](double t) { return t < t0 || t > 0.56; }), ts.end());
  Mesh m;
  const int ns = int(ss.size()), nt = int(ts.size());
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < ns; ++i) {
      m.points.push_back(Vec3(ss[i], ts[j] + Front::f(ss[i]), 0));
      metrics->push_back(Front::metric(m.points.back().x(), m.points.back().y()));
    }
  for (int j = 0; j + 1 < nt; ++j)
    for (int i = 0; i + 1 < ns; ++i) {
      const int a = j * ns + i;
      m.triangles.push_back({a, a + 1, a + ns + 1});
      m.triangles.push_back({a, a + ns + 1, a + ns});
    }
  return m;
}

}  // namespace

// The unit square's lower part [0, 1] x [0, top], whose top side crosses a graded layer of
// aspect ratio 100 through (0.5, 0.5) at the given angle; the mesher alone (no decomposition).
TEST(ObliqueLayer, PlanarMesherLeavesNoSliverFans) {
  // Placements that gave fans (min Q with 6 sweeps / with the sweeps run to the end, both
  // measured before the polishing pass came in): 10 deg at 0.45 0.062 / 0.590, 30 at 0.45
  // 0.010 / 0.746, 45 at 0.48 0.006 / 0.766, 60 at 0.5 0.009 / 0.755, 75 at 0.45 0.096 / 0.687.
  const double cases[][2] = {{10, 0.45}, {30, 0.45}, {45, 0.48}, {60, 0.5}, {75, 0.45}};
  for (const auto& [deg, top] : cases) {
    const double a = deg * kPi / 180, c = std::cos(a), s = std::sin(a);
    AnalyticControlSpace cs(Box2{{0.0, 0.0}, {1.0, 1.0}}, [=](const Vec2& p) {
      const double v = -s * (p.x() - 0.5) + c * (p.y() - 0.5);
      return Metric::fromSizes(a, 0.01, std::min(0.01, 0.0001 + 0.02 * std::abs(v)));
    });
    const std::vector<BoundaryLoop> loops{meshtest::metricPolygonLoop({{0, 0}, {1, 0}, {1, top}, {0, top}}, cs)};
    PlanarMesherOptions o;
    o.partElements = 0;
    const Mesh m = meshPlanarBoundary(loops, cs, o);
    meshtest::checkPlanarMesh(m, loops);
    EXPECT_GT(measureQuality(m, cs).qualityMin, 0.5) << deg << " degrees, top " << top;
  }
}

TEST(ObliqueLayer, RemeshOfAFrontPieceLeavesNoSliverFans) {
  // Three pieces: their boundaries meet the front's layer at other phases.
  for (double t0 : {0.40, 0.44, 0.47}) {
    std::vector<Metric> metrics;
    const Mesh carrier = frontPiece(t0, &metrics);
    std::unique_ptr<AdaptiveControlSpace> cs;
    const Mesh out = remesh(carrier, metrics, RemeshOptions{}, nullptr, &cs);
    ASSERT_GT(out.triangles.size(), 800u) << t0;
    const std::vector<double> q = elementQualities(out, *cs);
    const double qmin = *std::min_element(q.begin(), q.end());
    // Seen (before the polishing pass): 0.685-0.744 with the swaps run to the end,
    // 0.034-0.093 with 6 sweeps.
    EXPECT_GT(qmin, 0.5) << "t0 " << t0;
  }
}

// Randomized robustness: star-shaped outer polygons with a random hole, under random
// smoothly varying anisotropic metrics; every mesh must be valid and deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh_test_util.h"

using namespace anisomesh;
using namespace meshtest;

TEST(MeshRandom, StarPolygonsWithHolesUnderRandomMetrics) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 5 + static_cast<int>(u(rng) * 10);
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) angles.push_back(2 * M_PI * (i + 0.2 + 0.6 * u(rng)) / n);
    std::vector<Vec2> corners;
    for (double a : angles) corners.push_back((0.6 + 0.4 * u(rng)) * Vec2(std::cos(a), std::sin(a)));
    const double h0 = 0.03 + 0.04 * u(rng), ar = 1.0 + 9.0 * u(rng), phase = 6.0 * u(rng);
    AnalyticControlSpace cs({{-1, -1}, {1, 1}}, [=](const Vec2& p) {
      const double alpha = phase + 2.0 * p.x() + p.y();
      return Metric::fromSizes(alpha, h0, h0 * (1.0 + (ar - 1.0) * (0.5 + 0.5 * std::sin(3.0 * p.y() + phase))));
    });
    std::vector<BoundaryLoop> loops{metricPolygonLoop(corners, cs)};
    if (trial % 3 != 0) {
      const double r = 0.15 + 0.2 * u(rng);
      const int m = std::max(3, static_cast<int>(2 * M_PI * r / h0));
      loops.push_back(circleLoop(Vec2(0.1 * u(rng), 0.1 * u(rng)), r, m, trial % 2 == 0, 7));
    }
    PlanarMesherOptions opt;
    opt.quads = trial % 4 == 1;
    const Mesh a = meshPlanarBoundary(loops, cs, opt);
    SCOPED_TRACE("trial " + std::to_string(trial));
    checkPlanarMesh(a, loops);
    const QualityReport r = measureQuality(a, cs);
    EXPECT_EQ(r.inverted, 0);
    EXPECT_EQ(r.degenerate, 0);
    EXPECT_GT(r.qualityMean, 0.8);
    EXPECT_TRUE(sameMesh(a, meshPlanarBoundary(loops, cs, opt)));
  }
}

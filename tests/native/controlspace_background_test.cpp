// Background mesh control space: conforming bisection, point location, interpolation.
#include <gtest/gtest.h>
#include <memory>

#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "anisomesh/controlspace/background_mesh_control_space.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/error.h"
#include "controlspace_test_util.h"

using namespace anisomesh;

namespace {

using anisomesh::test_util::box;

using anisomesh::test_util::boundaryLayer;

// Conformity: every interior edge is shared by exactly two triangles with matching
// neighbour links, all triangles counter-clockwise, total area = box area.
void expectValidTriangulation(const BackgroundMeshControlSpace& bg) {
  std::map<std::pair<int, int>, int> edgeUse;
  double area = 0.0;
  for (int t = 0; t < bg.elementCount(); ++t) {
    const auto& v = bg.triangle(t);
    const Vec2 a = bg.nodePosition(v[0]), b = bg.nodePosition(v[1]), c = bg.nodePosition(v[2]);
    const double ar = 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    ASSERT_GT(ar, 0.0);
    area += ar;
    for (int k = 0; k < 3; ++k) {
      const int p = v[(k + 1) % 3], q = v[(k + 2) % 3];
      ++edgeUse[{std::min(p, q), std::max(p, q)}];
      const int n = bg.neighbours(t)[k];
      if (n >= 0) {
        bool back = false;
        for (int j = 0; j < 3; ++j) back = back || bg.neighbours(n)[j] == t;
        ASSERT_TRUE(back);
      }
    }
  }
  for (const auto& [e, uses] : edgeUse) ASSERT_LE(uses, 2);
  const Vec2 sz = bg.bounds().size();
  EXPECT_NEAR(area, sz.x() * sz.y(), 1e-12 * sz.x() * sz.y());
}

// A background mesh on [-1, 1] x [0, 1] refined down to 0.004 around (0.2, 0.4), its nodes'
// metrics varying in direction, size and stretch (strongly stretched near y = 0.4).
std::unique_ptr<BackgroundMeshControlSpace> refinedWithVaryingField(BackgroundInterpolation interp) {
  BackgroundMeshOptions o;
  o.interpolation = interp;
  auto made = std::make_unique<BackgroundMeshControlSpace>(box(-1.0, 0.0, 1.0, 1.0), o);
  BackgroundMeshControlSpace& bg = *made;
  bg.refine([&](const ControlElement& e) { return e.box.contains(Vec2(0.2, 0.4)) && e.size > 0.004; }, nullptr);
  for (int i = 0; i < bg.nodeCount(); ++i) {
    const Vec2 p = bg.nodePosition(i);
    bg.setNodeMetric(i, Metric::fromSizes(3.0 * p.x() + p.y(), 0.001 + 0.05 * std::fabs(p.y() - 0.4), 1.2 + p.x()));
  }
  return made;
}

}  // namespace

TEST(ControlSpaceBackground, InvalidBoxIsRejected) {
  try {
    BackgroundMeshControlSpace bg(box(0.0, 1.0, 1.0, 0.0));
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidDomain);
  }
  BackgroundMeshOptions o;
  o.initialGrid = 0;
  EXPECT_THROW(BackgroundMeshControlSpace(box(0.0, 0.0, 1.0, 1.0), o), Error);
}

TEST(ControlSpaceBackground, BisectionKeepsConformingTriangulation) {
  BackgroundMeshOptions o;
  o.initialGrid = 3;
  BackgroundMeshControlSpace bg(box(0.0, 0.0, 2.0, 1.0), o);
  expectValidTriangulation(bg);
  const Vec2 focus(0.7, 0.31);
  bg.refine([&](const ControlElement& e) { return e.box.contains(focus) && e.size > 0.003; }, nullptr);
  EXPECT_GT(bg.elementCount(), 50);
  expectValidTriangulation(bg);
  bg.bisect(0);
  expectValidTriangulation(bg);
}

TEST(ControlSpaceBackground, PointLocationAgreesWithBruteForce) {
  BackgroundMeshOptions o;
  o.initialGrid = 4;
  BackgroundMeshControlSpace bg(box(-1.0, 0.0, 1.0, 1.0), o);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(-1.0, 1.0), uy(0.0, 1.0);
  // Irregular refinement around a few random points.
  for (int k = 0; k < 6; ++k) {
    const Vec2 f(ux(rng), uy(rng));
    bg.refine([&](const ControlElement& e) { return e.box.contains(f) && e.size > 0.002; }, nullptr);
  }
  for (int k = 0; k < 3000; ++k) {
    const Vec2 p(ux(rng), uy(rng));
    const int t = bg.locateTriangle(p);
    ASSERT_TRUE(bg.triangleContains(t, p));
    int brute = -1;
    for (int u = 0; u < bg.elementCount() && brute < 0; ++u)
      if (bg.triangleContains(u, p)) brute = u;
    ASSERT_GE(brute, 0);
    if (brute != t) {
      // Only on a shared edge or vertex: both contain it.
      ASSERT_TRUE(bg.triangleContains(brute, p));
    }
  }
}

TEST(ControlSpaceBackground, InterpolationReturnsNodeMetricAtNodesAndConstants) {
  for (auto interp : {BackgroundInterpolation::InverseSquaredDistance, BackgroundInterpolation::Linear}) {
    BackgroundMeshOptions o;
    o.interpolation = interp;
    BackgroundMeshControlSpace bg(box(0.0, 0.0, 1.0, 1.0), o);
    bg.refine([&](const ControlElement& e) { return e.box.contains(Vec2(0.3, 0.3)) && e.size > 0.01; }, nullptr);
    const Metric c = Metric::fromSizes(0.4, 0.01, 0.2);
    for (int i = 0; i < bg.nodeCount(); ++i) bg.setNodeMetric(i, c);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 1000; ++k) {
      const Vec2 p(u(rng), u(rng));
      EXPECT_LT((bg.metricAt(p).transform() - c.transform()).norm(), 1e-9 * c.transform().norm());
    }
    for (int i = 0; i < bg.nodeCount(); ++i) bg.setNodeMetric(i, Metric::isotropic(0.01 + bg.nodePosition(i).x()));
    for (int i = 0; i < bg.nodeCount(); i += 5)
      EXPECT_NEAR(bg.metricAt(bg.nodePosition(i)).sizes().h1, 0.01 + bg.nodePosition(i).x(), 1e-12);
  }
  // Linear interpolation reproduces a linear Mt field.
  BackgroundMeshOptions o;
  o.interpolation = BackgroundInterpolation::Linear;
  BackgroundMeshControlSpace bg(box(0.0, 0.0, 1.0, 1.0), o);
  auto field = [](const Vec2& p) {
    Mat2 t;
    t << 3.0 + p.x(), 0.2 * p.y(), 0.2 * p.y(), 2.0 + p.y() - 0.5 * p.x();
    return t;
  };
  for (int i = 0; i < bg.nodeCount(); ++i) bg.setNodeMetric(i, Metric::fromTransform(field(bg.nodePosition(i))));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    const Vec2 p(u(rng), u(rng));
    EXPECT_LT((bg.metricAt(p).transform() - field(p)).norm(), 1e-12);
  }
}

TEST(ControlSpaceBackground, AdaptsToAnisotropicBoundaryLayer) {
  for (auto interp : {BackgroundInterpolation::InverseSquaredDistance, BackgroundInterpolation::Linear}) {
    BackgroundMeshOptions o;
    o.interpolation = interp;
    o.maxLevel = 12;
    BackgroundMeshControlSpace bg(box(0.0, 0.0, 1.0, 1.0), o);
    ContinuousInsertionOptions c;
    c.threshold = 0.3;
    c.sampleThreshold = 0.05;
    insertMetricFunction(bg, boundaryLayer, c);
    const double worst = anisomesh::test_util::worstLengthError(bg, boundaryLayer);
    EXPECT_LT(worst, 0.1) << "triangles " << bg.elementCount();
    EXPECT_GT(bg.metricAt(Vec2(0.3, 0.5)).aspectRatio(), 90.0);
    expectValidTriangulation(bg);
  }
}

// The refinement predicate's sample metrics (elementSampleMetric): with linear
// interpolation taken in the element itself, the same bits as metricAt at the centroid
// (inside one triangle only) and the same value up to rounding on the element's sides (the
// field is continuous there); with inverse distance weights, metricAt's answer itself.
TEST(ControlSpaceBackground, ElementSampleMetricIsTheQueryAtTheSample) {
  for (auto interp : {BackgroundInterpolation::Linear, BackgroundInterpolation::InverseSquaredDistance}) {
    const auto made = refinedWithVaryingField(interp);
    BackgroundMeshControlSpace& bg = *made;
    int checked = 0;
    bg.refine(
        [&](const ControlElement& e) {
          for (int k = 0; k < e.sampleCount; ++k) {
            const Mat2 a = bg.elementSampleMetric(e, k).transform(), b = bg.metricAt(e.samples[size_t(k)]).transform();
            if (k == 0 || interp == BackgroundInterpolation::InverseSquaredDistance)
              EXPECT_EQ(a, b) << "element " << e.id << " sample " << k;
            else
              EXPECT_LT((a - b).norm(), 1e-12 * b.norm()) << "element " << e.id << " sample " << k;
            ++checked;
          }
          return false;
        },
        nullptr);
    EXPECT_EQ(checked, 4 * bg.elementCount());
  }
}

// metricAtNear (the mesher's queries, walked from the previous query's triangle) gives
// metricAt's bits: along a path of small steps, at random jumps, on grid lines and nodes
// (where a point lies on shared edges), and from a stale or foreign hint.
TEST(ControlSpaceBackground, MetricAtNearIsMetricAt) {
  for (auto interp : {BackgroundInterpolation::Linear, BackgroundInterpolation::InverseSquaredDistance}) {
    const auto made = refinedWithVaryingField(interp);
    BackgroundMeshControlSpace& bg = *made;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ux(-1.0, 1.0), uy(0.0, 1.0), step(-0.002, 0.002);
    int hint = -1;
    Vec2 p(0.2, 0.4);
    auto check = [&](const Vec2& q) {
      ASSERT_EQ(bg.metricAtNear(q, hint).transform(), bg.metricAt(q).transform()) << q.transpose();
    };
    for (int k = 0; k < 20000; ++k) {
      p += Vec2(step(rng), step(rng));
      p = p.cwiseMax(Vec2(-1.2, -0.2)).cwiseMin(Vec2(1.2, 1.2));
      check(p);
      if (k % 97 == 0) check(Vec2(ux(rng), uy(rng)));
    }
    for (int i = 0; i < bg.nodeCount(); ++i) {
      const Vec2 n = bg.nodePosition(i);
      check(n);
      check(Vec2(n.x(), uy(rng)));
      check(Vec2(ux(rng), n.y()));
    }
    hint = bg.elementCount() + 5;
    check(Vec2(0.5, 0.5));
  }
}

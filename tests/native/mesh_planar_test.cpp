#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "anisomesh/core/error.h"
#include "mesh_test_util.h"

using namespace anisomesh;
using namespace meshtest;

namespace {

const Box2 kBox{{-1.0, -1.0}, {2.0, 2.0}};

void meshAndCheck(const std::vector<BoundaryLoop>& loops, double h, PlanarMesherOptions opt = {}) {
  UniformControlSpace cs(kBox, Metric::isotropic(h));
  const Mesh a = meshPlanarBoundary(loops, cs, opt);
  checkPlanarMesh(a, loops);
  const QualityReport r = measureQuality(a, cs);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_EQ(r.degenerate, 0);
  const Mesh b = meshPlanarBoundary(loops, cs, opt);
  EXPECT_TRUE(sameMesh(a, b)) << "meshing is not deterministic";
  if (!opt.boundaryOnly) {
    EXPECT_GT(r.qualityMean, 0.9);
    EXPECT_GT(r.edgesWithinSqrt2, 0.95);
  }
}

}  // namespace

TEST(MeshPlanar, UnitSquareUniform) { meshAndCheck({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 20)}, 0.05); }

TEST(MeshPlanar, LShapeUniform) {
  meshAndCheck({polygonLoop({{0, 0}, {1, 0}, {1, 0.5}, {0.5, 0.5}, {0.5, 1}, {0, 1}}, 10)}, 0.05);
}

TEST(MeshPlanar, ClockwiseOuterLoop) { meshAndCheck({polygonLoop({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, 10)}, 0.1); }

TEST(MeshPlanar, SquareWithSquareHole) {
  meshAndCheck({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 20),
                polygonLoop({{0.3, 0.3}, {0.3, 0.7}, {0.7, 0.7}, {0.7, 0.3}}, 8, 5)},
               0.05);
}

TEST(MeshPlanar, SquareWithCircularHoleEitherOrientation) {
  meshAndCheck({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 20), circleLoop({0.5, 0.5}, 0.25, 32, true)}, 0.05);
  meshAndCheck({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 20), circleLoop({0.4, 0.6}, 0.2, 25, false)}, 0.05);
}

TEST(MeshPlanar, TwoHoles) {
  meshAndCheck({polygonLoop({{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}}, 10), circleLoop({0.5, 0.5}, 0.25, 16),
                circleLoop({1.5, 0.5}, 0.25, 16, true)},
               0.1);
}

TEST(MeshPlanar, BoundaryOnly) {
  PlanarMesherOptions opt;
  opt.boundaryOnly = true;
  const std::vector<BoundaryLoop> loops{polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 20),
                                        circleLoop({0.5, 0.5}, 0.25, 32)};
  meshAndCheck(loops, 0.05, opt);
  UniformControlSpace cs(kBox, Metric::isotropic(0.05));
  const Mesh m = meshPlanarBoundary(loops, cs, opt);
  EXPECT_EQ(m.vertexCount(), 80 + 32);  // no inner node
}

// A 50x50 grid's points on the boundary of a square: long runs of collinear points,
// meshed with a coarse and a fine metric.
TEST(MeshPlanar, CollinearHeavyBoundary) {
  const std::vector<BoundaryLoop> loops{polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 49)};
  meshAndCheck(loops, 1.0 / 49.0);
  UniformControlSpace coarse(kBox, Metric::isotropic(0.3));
  const Mesh m = meshPlanarBoundary(loops, coarse);
  checkPlanarMesh(m, loops);
  PlanarMesherOptions opt;
  opt.boundaryOnly = true;
  checkPlanarMesh(meshPlanarBoundary(loops, coarse, opt), loops);
}

// All boundary points cocircular (regular polygons), holes too.
TEST(MeshPlanar, CocircularBoundary) {
  const std::vector<BoundaryLoop> loops{circleLoop({0, 0}, 1.0, 128), circleLoop({0, 0}, 0.5, 64, true),
                                        circleLoop({0.0, 0.75}, 0.1, 16)};
  PlanarMesherOptions opt;
  opt.boundaryOnly = true;
  meshAndCheck(loops, 0.05, opt);
  meshAndCheck(loops, 0.05);
}

TEST(MeshPlanar, CocircularAnnulus) {
  meshAndCheck({circleLoop({0.5, 0.5}, 1.0, 128), circleLoop({0.5, 0.5}, 0.5, 64, true)}, 0.05);
}

TEST(MeshPlanar, InvalidInput) {
  UniformControlSpace cs(kBox, Metric::isotropic(0.1));
  auto code = [&](const std::vector<BoundaryLoop>& loops) {
    try {
      meshPlanarBoundary(loops, cs);
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Internal;
  };
  EXPECT_EQ(code({}), ErrorCode::InvalidArgument);
  EXPECT_EQ(code({makeLoop({{0, 0}, {1, 0}})}), ErrorCode::InvalidArgument);
  BoundaryLoop badRefs = makeLoop({{0, 0}, {1, 0}, {0, 1}});
  badRefs.edgeRefs.pop_back();
  EXPECT_EQ(code({badRefs}), ErrorCode::InvalidArgument);
  EXPECT_EQ(code({makeLoop({{0, 0}, {1, 0}, {0, NAN}})}), ErrorCode::InvalidArgument);
  EXPECT_EQ(code({makeLoop({{0, 0}, {1, 0}, {1, 0}, {0, 1}})}), ErrorCode::InvalidArgument);          // duplicate
  EXPECT_EQ(code({makeLoop({{0, 0}, {1, 0}, {0, 1}, {1, 1}})}), ErrorCode::SelfIntersectingContour);  // bow tie
  const BoundaryLoop square = polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 10);
  EXPECT_EQ(code({square, circleLoop({2.0, 0.5}, 0.2, 12)}), ErrorCode::HoleOutsideDomain);
  EXPECT_EQ(code({square, circleLoop({0.5, 0.5}, 0.3, 16), circleLoop({0.5, 0.5}, 0.1, 8)}),
            ErrorCode::HoleOutsideDomain);                                                   // hole inside a hole
  EXPECT_EQ(code({circleLoop({0.5, 0.5}, 0.3, 16), square}), ErrorCode::HoleOutsideDomain);  // outer inside hole
  EXPECT_EQ(code({square, circleLoop({1.0, 0.53}, 0.2, 12)}), ErrorCode::SelfIntersectingContour);  // crossing
}

TEST(MeshPlanar, ElementBudgetExceeded) {
  UniformControlSpace cs(kBox, Metric::isotropic(0.01));
  PlanarMesherOptions opt;
  opt.maxElements = 1000;
  try {
    meshPlanarBoundary({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 100)}, cs, opt);
    FAIL() << "expected ElementBudgetExceeded";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ElementBudgetExceeded);
    EXPECT_NE(std::string(e.what()).find("1000"), std::string::npos) << e.what();
  }
}

TEST(MeshPlanar, CancellationThroughProgress) {
  UniformControlSpace cs(kBox, Metric::isotropic(0.01));
  PlanarMesherOptions opt;
  int calls = 0;
  double last = -1.0;
  bool monotone = true;
  opt.progress = [&](double f) {
    monotone = monotone && f >= last;
    last = f;
    return ++calls < 3;
  };
  try {
    meshPlanarBoundary({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 100)}, cs, opt);
    FAIL() << "expected Cancelled";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Cancelled);
  }
  EXPECT_EQ(calls, 3);
  EXPECT_TRUE(monotone);
  // Without cancellation the progress reaches 1.
  opt.progress = [&](double f) {
    last = f;
    return true;
  };
  const Mesh m = meshPlanarBoundary({polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 100)}, cs, opt);
  EXPECT_EQ(last, 1.0);
  EXPECT_GT(m.triangles.size(), 10000u);
}

// Far from the origin and tiny: the exact predicates keep the topology right.
TEST(MeshPlanar, LargeOffsetAndTinyScale) {
  const Vec2 o(1.0e6, -3.0e6);
  const double s = 1e-3;
  std::vector<Vec2> corners{o, o + Vec2(s, 0), o + Vec2(s, s), o + Vec2(0, s)};
  const std::vector<BoundaryLoop> loops{polygonLoop(corners, 20), circleLoop(o + Vec2(0.5 * s, 0.5 * s), 0.25 * s, 24)};
  UniformControlSpace cs(Box2{o - Vec2(1, 1), o + Vec2(1, 1)}, Metric::isotropic(0.05 * s));
  const Mesh m = meshPlanarBoundary(loops, cs);
  checkPlanarMesh(m, loops);
  const QualityReport r = measureQuality(m, cs);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_GT(r.qualityMean, 0.9);
}

// Without improvement passes the mesh is still valid (frontal insertion alone).
TEST(MeshPlanar, NoImprovementPasses) {
  PlanarMesherOptions opt;
  opt.improvementPasses = 0;
  UniformControlSpace cs(kBox, Metric::isotropic(0.05));
  const std::vector<BoundaryLoop> loops{polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 20),
                                        circleLoop({0.5, 0.5}, 0.25, 32, true)};
  const Mesh m = meshPlanarBoundary(loops, cs, opt);
  checkPlanarMesh(m, loops);
  EXPECT_GT(measureQuality(m, cs).qualityMean, 0.85);
  opt.improvementPasses = -1;
  EXPECT_THROW(meshPlanarBoundary(loops, cs, opt), Error);
}

// A boundary-only run (a section 3.2 check) leaves its boundary triangulation in the cache;
// a full run on equal loops starts from it and makes the mesh a run without the cache makes.
// Loops that differ (one point moved) are triangulated again, not taken from the cache.
TEST(MeshPlanar, BoundaryTriangulationCacheGivesTheSameMesh) {
  const std::vector<BoundaryLoop> loops = {polygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 20),
                                           circleLoop({0.5, 0.5}, 0.25, 48, true)};
  const UniformControlSpace cs(kBox, Metric::fromSizes(0.4, 0.06, 0.015));
  const Mesh plain = meshPlanarBoundary(loops, cs);
  PlanarMesherOptions check;
  check.boundaryOnly = true;
  check.boundaryCache = makeBoundaryTriangulationCache();
  const Mesh boundary = meshPlanarBoundary(loops, cs, check);
  EXPECT_TRUE(sameMesh(boundary, meshPlanarBoundary(loops, cs, [] {
                         PlanarMesherOptions o;
                         o.boundaryOnly = true;
                         return o;
                       }())));
  MesherTimings timings;
  PlanarMesherOptions full;
  full.boundaryCache = check.boundaryCache;
  full.timings = &timings;
  EXPECT_TRUE(sameMesh(meshPlanarBoundary(loops, cs, full), plain));
  EXPECT_TRUE(timings.boundaryFromCache);
  auto moved = loops;
  moved[1].points[3] += Vec2(0.01, 0.0);
  const Mesh other = meshPlanarBoundary(moved, cs, full);
  EXPECT_FALSE(timings.boundaryFromCache);
  EXPECT_TRUE(sameMesh(other, meshPlanarBoundary(moved, cs)));
  EXPECT_FALSE(sameMesh(other, plain));
}

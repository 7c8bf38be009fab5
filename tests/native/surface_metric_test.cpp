#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/surface_metric.h"

using namespace anisomesh;

namespace {

constexpr double kPiMetric = 3.14159265358979323846;

// 3D length of the parameter vector of unit metric length in direction angle.
double size3D(const Surface& s, const Vec2& uv, const Metric& m, double angle) {
  const Vec2 dir(std::cos(angle), std::sin(angle));
  const Vec2 du = dir / m.length(dir);
  return (s.derivatives(uv).jacobian() * du).norm();
}

SurfaceMetricOptions looseBounds(double tol) {
  SurfaceMetricOptions o;
  o.chordTolerance = tol;
  o.hmin = 1e-6;
  o.hmax = 1e3;
  o.maxAspectRatio = 1e3;
  return o;
}

}  // namespace

TEST(SurfaceMetric, SphereGivesChordSizeInEveryTangentDirection) {
  const double R = 2.0, tol = 1e-3, h = std::sqrt(8 * tol * R);
  const SphereSurface s(R);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0, 2 * kPiMetric), v(-1.35, 1.35), a(0, kPiMetric);
  for (int i = 0; i < 50; ++i) {
    const Vec2 uv(u(rng), v(rng));
    const Metric m = parameterMetric(s, uv, looseBounds(tol));
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(size3D(s, uv, m, a(rng)), h, 1e-10 * h) << uv.transpose();
    // The same holds for the 3D metric itself.
    const TangentMetric t = requestedMetric3D(s, uv, looseBounds(tol));
    EXPECT_NEAR(t.h1, h, 1e-12);
    EXPECT_NEAR(t.h2, h, 1e-12);
  }
}

TEST(SurfaceMetric, SphereChordOfRequestedLengthDeviatesByTheTolerance) {
  const double R = 2.0, tol = 1e-3, h = std::sqrt(8 * tol * R);
  const SphereSurface s(R);
  // Along the equator the parameter step for a chord of length h is 2 asin(h / 2R).
  const double du = 2 * std::asin(h / (2 * R));
  const double dev = chordDeviation(s, {0.3, 0.0}, {0.3 + du, 0.0}, ChordDeviationOptions{63});
  EXPECT_NEAR(dev, tol, 0.01 * tol);  // sagitta R (1 - cos(du/2)) ~ h^2 / 8R
  EXPECT_NEAR(dev, R * (1 - std::cos(du / 2)), 1e-12);
  const PlaneSurface plane(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_NEAR(chordDeviation(plane, {0, 0}, {1, 0.5}), 0, 1e-15);
}

TEST(SurfaceMetric, CylinderAxialSizeIsHmaxOrTheAspectCap) {
  const double R = 0.5, tol = 1e-3, hc = std::sqrt(8 * tol * R);
  const CylinderSurface s(R);
  const Vec2 uv(1.0, 0.4);
  SurfaceMetricOptions o = looseBounds(tol);
  o.hmax = 0.5;
  o.maxAspectRatio = 100;  // hmax binds: 0.5 < 100 hc
  Metric m = parameterMetric(s, uv, o);
  EXPECT_NEAR(size3D(s, uv, m, 0.0), hc, 1e-12);                // around (u)
  EXPECT_NEAR(size3D(s, uv, m, kPiMetric / 2), o.hmax, 1e-12);  // along the axis (v)
  o.maxAspectRatio = 3;                                         // the cap binds: 3 hc < 0.5
  m = parameterMetric(s, uv, o);
  EXPECT_NEAR(size3D(s, uv, m, 0.0), hc, 1e-12);
  EXPECT_NEAR(size3D(s, uv, m, kPiMetric / 2), 3 * hc, 1e-12);
  // The 3D metric agrees: h1 belongs to k1 = 0 (axis), h2 to k2 = -1/R.
  const TangentMetric t = requestedMetric3D(s, uv, o);
  EXPECT_NEAR(t.h1, 3 * hc, 1e-12);
  EXPECT_NEAR(t.h2, hc, 1e-12);
  EXPECT_NEAR(t.hn, hc, 1e-12);
}

TEST(SurfaceMetric, SizesAreClampedAndAngleToleranceApplies) {
  SurfaceMetricOptions o = looseBounds(1e-3);
  EXPECT_NEAR(curvatureSize(2.0, o), std::sqrt(8e-3 / 2.0), 1e-15);
  EXPECT_NEAR(curvatureSize(-2.0, o), std::sqrt(8e-3 / 2.0), 1e-15);
  EXPECT_EQ(curvatureSize(0.0, o), o.hmax);
  o.angleTolerance = 0.01;  // 0.01 / 2 = 0.005 < 0.063
  EXPECT_NEAR(curvatureSize(2.0, o), 0.005, 1e-15);
  o.hmin = 0.01;
  EXPECT_EQ(curvatureSize(2.0, o), 0.01);
  o.hmax = 0.02;
  EXPECT_EQ(curvatureSize(1e-9, o), 0.02);
}

TEST(SurfaceMetric, PaperP2MetricIsFiniteAndSpdOnAGrid) {
  const auto p2 = paperP2();
  SurfaceMetricOptions o;
  o.chordTolerance = 0.005;
  o.hmin = 0.01;
  o.hmax = 2.0;
  o.maxAspectRatio = 8;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const Vec2 uv(-10 + 0.5 * i, -10 + 0.5 * j);
      const Metric m = parameterMetric(*p2, uv, o);
      const Mat2 t = m.tensor();
      ASSERT_TRUE(t.allFinite()) << uv.transpose();
      Eigen::SelfAdjointEigenSolver<Mat2> es(t);
      ASSERT_GT(es.eigenvalues().minCoeff(), 0) << uv.transpose();
      for (double a = 0; a < kPiMetric; a += kPiMetric / 6) {
        const double h = size3D(*p2, uv, m, a);
        EXPECT_GE(h, o.hmin * (1 - 1e-9));
        EXPECT_LE(h, o.hmax * (1 + 1e-9));
      }
      const TangentMetric tm = requestedMetric3D(*p2, uv, o);
      EXPECT_LE(std::max(tm.h1, tm.h2), o.maxAspectRatio * std::min(tm.h1, tm.h2) * (1 + 1e-12));
    }
}

TEST(SurfaceMetric, DegeneratePointIsInvalidSurfaceWithThePoint) {
  const auto s =
      std::make_shared<SphereSurface>(1.0, Vec3::Zero(), Box2{{0, -kPiMetric / 2}, {2 * kPiMetric, kPiMetric / 2}});
  try {
    parameterMetric(*s, {0.3, kPiMetric / 2}, SurfaceMetricOptions{});
    ADD_FAILURE() << "expected InvalidSurface";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidSurface);
    EXPECT_NE(std::string(e.what()).find("(u, v) = (0.3, 1.570796327)"), std::string::npos) << e.what();
  }
  const SurfaceCurvatureControlSpace cs(s, SurfaceMetricOptions{});
  EXPECT_THROW(cs.metricAt({0.3, kPiMetric / 2}), Error);
  EXPECT_NO_THROW(cs.metricAt({0.3, 1.0}));
  EXPECT_FALSE(cs.tryMetricAt({0.3, kPiMetric / 2}).has_value());
  ASSERT_TRUE(cs.tryMetricAt({0.3, 1.0}).has_value());
  EXPECT_LT((cs.tryMetricAt({0.3, 1.0})->tensor() - cs.metricAt({0.3, 1.0}).tensor()).norm(), 1e-15);
}

TEST(SurfaceMetric, ParameterizationMatrixMeasures3DLength) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> t(0.0, 1.0), d(-1.0, 1.0);
  const std::shared_ptr<Surface> surfaces[] = {paperP2(), std::make_shared<SphereSurface>(3.0),
                                               std::make_shared<TorusSurface>(2.0, 0.5),
                                               std::make_shared<CylinderSurface>(0.2)};
  for (const auto& s : surfaces) {
    const Box2 b = s->domain();
    for (int i = 0; i < 30; ++i) {
      const Vec2 uv = b.lo + Vec2(t(rng) * b.size().x(), t(rng) * b.size().y());
      const Mat2 mp = parameterizationMatrix(*s, uv);
      EXPECT_NEAR(mp(0, 1), mp(1, 0), 1e-15);
      const Vec2 du(d(rng), d(rng));
      const double l3 = (s->derivatives(uv).jacobian() * du).norm();
      EXPECT_NEAR((mp * du).norm(), l3, 1e-12 * (1 + l3)) << s->name();
    }
  }
}

TEST(SurfaceMetric, ControlSpaceMatchesMetricAndIntersectsUserMetrics) {
  const double R = 2.0, tol = 1e-3, h = std::sqrt(8 * tol * R);
  const auto s = std::make_shared<SphereSurface>(R);
  SurfaceCurvatureControlSpace cs(s, looseBounds(tol));
  const Vec2 uv(1.0, 0.5);
  EXPECT_LT((cs.metricAt(uv).tensor() - parameterMetric(*s, uv, looseBounds(tol)).tensor()).norm(), 1e-12);
  EXPECT_LT((cs.parameterizationAt(uv) - parameterizationMatrix(*s, uv)).norm(), 1e-15);
  EXPECT_EQ(cs.bounds().hi, s->domain().hi);
  // Outside the domain the query is clamped.
  EXPECT_LT((cs.metricAt({1.0, 5.0}).tensor() - cs.metricAt({1.0, 1.4}).tensor()).norm(), 1e-12);

  // A finer isotropic 3D user metric wins everywhere: 3D sizes become h / 2.
  cs.setUserMetric3D([h](const Vec3&) { return Mat3(Mat3::Identity() / (0.25 * h * h)); });
  Metric m = cs.metricAt(uv);
  for (double a : {0.0, 0.7, 2.0}) EXPECT_NEAR(size3D(*s, uv, m, a), 0.5 * h, 1e-9 * h);
  // A 2D user metric finer along u only.
  const Metric user = Metric::fromSizes(0.0, 1e-3, 1e3);
  cs.setUserMetric([&](const Vec2&) { return user; });
  m = cs.metricAt(uv);
  EXPECT_NEAR(m.sizeAlong(Vec2(1, 0)), 1e-3, 1e-12);
  EXPECT_NEAR(size3D(*s, uv, m, kPiMetric / 2), 0.5 * h, 1e-9 * h);
}

TEST(SurfaceMetric, EdgeLengthAndQualityIn3D) {
  EXPECT_NEAR(edgeLength3D(Vec3(0, 0, 0), Vec3(3, 4, 0), Mat3::Identity()), 5, 1e-15);
  EXPECT_NEAR(edgeLength3D(Vec3(0, 0, 0), Vec3(0, 0, 2), Mat3(Vec3(1, 1, 4).asDiagonal())), 4, 1e-15);
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2, 0);
  EXPECT_NEAR(triangleQuality3D(a, b, c, Mat3::Identity()), 1, 1e-14);
  EXPECT_NEAR(triangleQuality3D(a, b, c, Mat3(Vec3(4, 1, 1).asDiagonal())),
              4 * std::sqrt(3.0) * (std::sqrt(3.0) / 2) / (4 + 1.75 + 1.75), 1e-14);  // x stretched by 2
  EXPECT_EQ(triangleQuality3D(a, b, Vec3(2, 0, 0), Mat3::Identity()), 0);

  // On a sphere, an edge whose 3D length is the requested size has metric length ~1.
  const double R = 2.0, tol = 1e-3, h = std::sqrt(8 * tol * R);
  const SphereSurface s(R);
  const double du = 2 * std::asin(h / (2 * R));
  EXPECT_NEAR(edgeLength3D(s, {0.2, 0.0}, {0.2 + du, 0.0}, looseBounds(tol)), 1.0, 1e-9);
  // An equilateral (in 3D) small triangle on the sphere has Q close to 1.
  const double dv = du;  // near the equator u and v scale alike
  const double q =
      triangleQuality3D(s, {0.2, 0.0}, {0.2 + du, 0.0}, {0.2 + 0.5 * du, dv * std::sqrt(3.0) / 2}, looseBounds(tol));
  EXPECT_NEAR(q, 1.0, 1e-3);
  // A plane with isotropic hmax sizing: Q is the Euclidean quality.
  const PlaneSurface plane(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_NEAR(triangleQuality3D(plane, {0, 0}, {1, 0}, {0, 1}, SurfaceMetricOptions{}), 4 * std::sqrt(3.0) * 0.5 / 4,
              1e-14);
}

TEST(SurfaceMetric, OptionsAreValidated) {
  auto bad = [](auto mutate) {
    SurfaceMetricOptions o;
    mutate(o);
    try {
      validate(o);
    } catch (const Error& e) {
      return e.code() == ErrorCode::InvalidArgument;
    }
    return false;
  };
  EXPECT_TRUE(bad([](SurfaceMetricOptions& o) { o.hmin = 0; }));
  EXPECT_TRUE(bad([](SurfaceMetricOptions& o) { o.hmax = o.hmin / 2; }));
  EXPECT_TRUE(bad([](SurfaceMetricOptions& o) { o.maxAspectRatio = 0.5; }));
  EXPECT_TRUE(bad([](SurfaceMetricOptions& o) { o.chordTolerance = NAN; }));
  EXPECT_FALSE(bad([](SurfaceMetricOptions&) {}));
  EXPECT_THROW(SurfaceCurvatureControlSpace(nullptr, SurfaceMetricOptions{}), Error);
  EXPECT_THROW(chordDeviation(SphereSurface(1), {0, 0}, {1, 0}, ChordDeviationOptions{0}), Error);
}

TEST(SurfaceMetric, TangentBasisMetricPullsBackToTheParameterMetric) {
  const TorusSurface s(3.0, 1.0);
  SurfaceMetricOptions o = looseBounds(1e-3);
  o.maxAspectRatio = 1.5;
  for (const Vec2& uv : {Vec2(0.3, 0.4), Vec2(2.0, 3.0), Vec2(5.0, 1.2)}) {
    const TangentMetric t = requestedMetric3D(s, uv, o);
    const Metric a = pullBackTangentMetric(t.inTangentBasis(), t.dir1, t.dir2, s.derivatives(uv));
    const Metric b = parameterMetric(s, uv, o);
    const Metric c = pullBackMetric(t.tensor(), s.derivatives(uv));
    EXPECT_LT((a.tensor() - b.tensor()).norm(), 1e-10 * b.tensor().norm());
    EXPECT_LT((c.tensor() - b.tensor()).norm(), 1e-10 * b.tensor().norm());
    // Along each principal direction the 3D size is h_i.
    const SurfaceCurvature k = curvature(s, uv);
    EXPECT_NEAR(1.0 / b.length(k.uvDir1), t.h1, 1e-10 * t.h1);
    EXPECT_NEAR(1.0 / b.length(k.uvDir2), t.h2, 1e-10 * t.h2);
  }
}

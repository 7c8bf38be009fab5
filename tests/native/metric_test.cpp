#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "anisomesh/anisomesh.h"
#include "anisomesh/metric/metric_ellipse.h"
#include "anisomesh/metric/sym_eigen.h"

using namespace anisomesh;

namespace {

Vec2 dir(double angle) { return {std::cos(angle), std::sin(angle)}; }

}  // namespace

TEST(Metric, FromSizesGivesRequestedLengthsAlongAxes) {
  const double alpha = 0.3;
  const Metric m = Metric::fromSizes(alpha, 0.01, 2.0);
  EXPECT_NEAR(m.sizeAlong(dir(alpha)), 0.01, 1e-14);
  EXPECT_NEAR(m.sizeAlong(dir(alpha + M_PI / 2)), 2.0, 1e-12);
  EXPECT_NEAR(m.length(0.01 * dir(alpha)), 1.0, 1e-12);
  EXPECT_NEAR(m.aspectRatio(), 200.0, 1e-9);
}

TEST(Metric, TransformIsSymmetricSquareRoot) {
  const Metric m = Metric::fromSizes(-1.1, 0.5, 3.0);
  const Mat2 mt = m.transform();
  EXPECT_NEAR(mt(0, 1), mt(1, 0), 1e-15);
  const Mat2 expected = [] {
    const double c = std::cos(-1.1), s = std::sin(-1.1);
    Mat2 r;
    r << c, -s, s, c;
    return Mat2(r * Eigen::Vector2d(1 / 0.25, 1 / 9.0).asDiagonal() * r.transpose());
  }();
  EXPECT_LT((mt * mt.transpose() - expected).norm(), 1e-12);
  EXPECT_LT((m.tensor() - expected).norm(), 1e-12);
}

TEST(Metric, SizesRoundTrip) {
  const Metric m = Metric::fromSizes(0.7, 0.2, 0.05);
  const MetricSizes s = m.sizes();
  EXPECT_NEAR(s.h1, 0.05, 1e-12);  // h1 is the smaller size
  EXPECT_NEAR(s.h2, 0.2, 1e-12);
  // The h1 direction is the normal of alpha = 0.7.
  EXPECT_NEAR(std::abs(std::cos(s.alpha - (0.7 + M_PI / 2))), 1.0, 1e-12);
  const Metric back = Metric::fromSizes(s.alpha, s.h1, s.h2);
  EXPECT_LT((back.tensor() - m.tensor()).norm(), 1e-9 * m.tensor().norm());
}

TEST(Metric, FromTensorMatchesFromSizes) {
  const Metric a = Metric::fromSizes(0.4, 0.1, 1.0);
  const Mat2 t = a.tensor();
  const Metric b = Metric::fromTensor(t(0, 0), t(0, 1), t(1, 1));
  EXPECT_LT((a.transform() - b.transform()).norm(), 1e-10);
}

TEST(Metric, RejectsBadSizes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double h : {0.0, -1.0, nan, inf}) {
    try {
      Metric::fromSizes(0.0, h, 1.0);
      FAIL() << "accepted h1 = " << h;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::InvalidMetric);
      EXPECT_NE(std::string(e.what()).find("h1"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(Metric::fromSizes(nan, 1.0, 1.0), Error);
  EXPECT_THROW(Metric::isotropic(-2.0), Error);
}

TEST(Metric, RejectsNonSpdTensor) {
  try {
    Metric::fromTensor(1.0, 2.0, 1.0);  // eigenvalues 3 and -1
    FAIL() << "accepted an indefinite tensor";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidMetric);
    EXPECT_NE(std::string(e.what()).find("positive definite"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Metric::fromTensor(0.0, 0.0, 1.0), Error);
  EXPECT_THROW(Metric::fromTensor(-1.0, 0.0, -1.0), Error);
  Mat2 asym;
  asym << 1.0, 0.5, 0.0, 1.0;
  EXPECT_THROW(Metric::fromTensor(asym), Error);
  EXPECT_THROW(Metric::fromTensor(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0), Error);
}

TEST(Metric, IntersectionLiesInsideBothUnitBalls) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), logh(std::log(1e-3), std::log(10.0));
  for (int trial = 0; trial < 400; ++trial) {
    const Metric a = Metric::fromSizes(angle(rng), std::exp(logh(rng)), std::exp(logh(rng)));
    const Metric b = Metric::fromSizes(angle(rng), std::exp(logh(rng)), std::exp(logh(rng)));
    const Metric c = intersect(a, b);
    for (int k = 0; k < 64; ++k) {
      const Vec2 d = dir(2 * M_PI * k / 64.0);
      // The result asks for lengths no larger than either input, in every direction.
      EXPECT_LE(c.sizeAlong(d), a.sizeAlong(d) * (1 + 1e-9));
      EXPECT_LE(c.sizeAlong(d), b.sizeAlong(d) * (1 + 1e-9));
    }
    // And it is the largest such ellipse along the common eigen-directions: it touches
    // one of the two in at least one direction.
    double touch = 1e300;
    for (int k = 0; k < 4000; ++k) {
      const Vec2 d = dir(M_PI * k / 4000.0);
      touch = std::min(touch, std::min(a.sizeAlong(d), b.sizeAlong(d)) / c.sizeAlong(d));
    }
    EXPECT_NEAR(touch, 1.0, 1e-3);
  }
}

// intersect() builds Q = I + (l1 - 1) v1 v1^T from N's entries (no angle): checked against
// the eigen-decomposition done in long double (80-bit on x86; plain double where long
// double is), on pairs with sizes 1e-4..1 (aspect up to 1e4), length by length.
TEST(Metric, IntersectionMatchesALongDoubleReference) {
  using LD = long double;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), logh(std::log(1e-4), 0.0);
  double worst = 0.0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Metric a = Metric::fromSizes(angle(rng), std::exp(logh(rng)), std::exp(logh(rng)));
    const Metric b = Metric::fromSizes(angle(rng), std::exp(logh(rng)), std::exp(logh(rng)));
    const Mat2 ta = a.transform(), mb = b.tensor();
    // N = Mt_a^-1 M_b Mt_a^-1 in long double.
    const LD det = static_cast<LD>(ta(0, 0)) * ta(1, 1) - static_cast<LD>(ta(0, 1)) * ta(1, 0);
    const LD i00 = ta(1, 1) / det, i01 = -ta(0, 1) / det, i11 = ta(0, 0) / det;
    const LD t00 = i00 * mb(0, 0) + i01 * mb(1, 0), t01 = i00 * mb(0, 1) + i01 * mb(1, 1);
    const LD t10 = i01 * mb(0, 0) + i11 * mb(1, 0), t11 = i01 * mb(0, 1) + i11 * mb(1, 1);
    const LD n00 = t00 * i00 + t01 * i01, n01 = t00 * i01 + t01 * i11, n11 = t10 * i01 + t11 * i11;
    const LD half = (n00 - n11) / 2, r = std::sqrt(half * half + n01 * n01), mean = (n00 + n11) / 2;
    const LD l1 = mean + r, l2 = mean - r, th = std::atan2(2 * n01, n00 - n11) / 2;
    const LD c = std::cos(th), s = std::sin(th);
    const LD q1 = std::max(l1, LD(1)), q2 = std::max(l2, LD(1));
    const LD q00 = q1 * c * c + q2 * s * s, q01 = (q1 - q2) * c * s, q11 = q1 * s * s + q2 * c * c;
    // M = Mt_a Q Mt_a.
    const LD u00 = ta(0, 0) * q00 + ta(0, 1) * q01, u01 = ta(0, 0) * q01 + ta(0, 1) * q11;
    const LD u10 = ta(1, 0) * q00 + ta(1, 1) * q01, u11 = ta(1, 0) * q01 + ta(1, 1) * q11;
    const LD m00 = u00 * ta(0, 0) + u01 * ta(1, 0), m01 = u00 * ta(0, 1) + u01 * ta(1, 1);
    const LD m11 = u10 * ta(0, 1) + u11 * ta(1, 1);
    const Mat2 got = intersect(a, b).tensor();
    // Each direction's requested length against the reference's own (the coarse direction
    // is judged on its own scale, not on the fine one's).
    const LD refAngle = std::atan2(2 * m01, m00 - m11) / 2;  // the reference's eigen-directions first
    for (int k = -2; k < 32; ++k) {
      const LD th2 = k < 0 ? refAngle + (k + 2) * LD(M_PI / 2) : LD(M_PI) * k / 32;
      const LD dx = std::cos(th2), dy = std::sin(th2);
      const LD want = dx * dx * m00 + 2 * dx * dy * m01 + dy * dy * m11;
      const LD have = dx * dx * got(0, 0) + dx * dy * (got(0, 1) + got(1, 0)) + dy * dy * got(1, 1);
      worst = std::max(worst, static_cast<double>(std::abs(std::sqrt(have / want) - 1)));
    }
  }
  // Measured: 2.7e-9 (the former angle form: 1.3e-9), where the tensors' condition reaches
  // 1e8; w = (l1 - 1) / l1 in place of (l1 - 1) / (l1 - l2) gives 0.12.
  EXPECT_LT(worst, 1e-8);
}

TEST(Metric, IntersectionReturnsTheSmallerMetric) {
  const Metric small = Metric::fromSizes(0.3, 0.1, 0.2);
  const Metric large = Metric::fromSizes(1.2, 0.5, 0.9);
  EXPECT_LT((intersect(small, large).tensor() - small.tensor()).norm(), 1e-9 * small.tensor().norm());
  EXPECT_LT((intersect(large, small).tensor() - small.tensor()).norm(), 1e-9 * small.tensor().norm());
  // Crossed stretches give the isotropic fine metric.
  const Metric h = Metric::fromSizes(0.0, 0.1, 1.0), v = Metric::fromSizes(M_PI / 2, 0.1, 1.0);
  const Metric c = intersect(h, v);
  EXPECT_NEAR(c.sizeAlong(dir(0)), 0.1, 1e-12);
  EXPECT_NEAR(c.sizeAlong(dir(M_PI / 2)), 0.1, 1e-12);
}

TEST(Metric, InterpolationActsOnTransform) {
  const Metric a = Metric::fromSizes(0.0, 1.0, 1.0), b = Metric::fromSizes(0.0, 0.5, 0.25);
  const Metric mid = interpolate(a, b, 0.5);
  EXPECT_LT((mid.transform() - 0.5 * (a.transform() + b.transform())).norm(), 1e-15);
  EXPECT_NEAR(mid.sizeAlong(dir(0)), 1.0 / 1.5, 1e-14);
  EXPECT_LT((interpolate(a, b, 0.0).transform() - a.transform()).norm(), 1e-15);
  EXPECT_LT((interpolate(a, b, 1.0).transform() - b.transform()).norm(), 1e-15);
}

TEST(Metric, DifferenceIsZeroOnlyForEqualMetrics) {
  const Metric a = Metric::fromSizes(0.2, 0.1, 0.4);
  EXPECT_NEAR(difference(a, a), 0.0, 1e-12);
  EXPECT_NEAR(difference(a, a.scaled(2.0)), 1.0, 1e-12);  // lengths double
  EXPECT_NEAR(difference(a, a.scaled(0.5)), 1.0, 1e-12);  // lengths halve
  EXPECT_GT(difference(a, Metric::fromSizes(0.25, 0.1, 0.4)), 0.01);
}

// The drawn unit ball: every point at metric distance scale from the centre, from angle 0
// counter-clockwise, and the segment count checked.
TEST(MetricEllipse, PointsLieOnTheScaledUnitBall) {
  const Metric m = Metric::fromSizes(0.6, 0.02, 0.3);
  const Vec2 c(1.5, -2.0);
  const auto pts = metricEllipse(m, c, 24, 0.5);
  ASSERT_EQ(pts.size(), 24u);
  for (const Vec2& p : pts) EXPECT_NEAR(m.length(p - c), 0.5, 1e-12);
  EXPECT_NEAR((m.transform() * (pts[0] - c) - Vec2(0.5, 0.0)).norm(), 0.0, 1e-12);  // angle 0 first
  const Vec2 a = m.transform() * (pts[1] - c), b = m.transform() * (pts[2] - c);
  EXPECT_GT(a.x() * b.y() - a.y() * b.x(), 0.0);  // counter-clockwise in metric space
  EXPECT_THROW(metricEllipse(m, c, 2), Error);
  EXPECT_THROW(metricEllipse(m, c, 100001), Error);
}

TEST(Metric, TensorsNearSingularAreCheckedByTheirEigenvalues) {
  // fromTensor accepts exactly the finite tensors whose smaller eigenvalue (as
  // symEigenValues computes it) is positive, also when a cheaper test decides.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 200000; ++i) {
    const double scale = std::pow(10.0, -120.0 + 240.0 * u(rng));
    const double a = scale * (0.01 + u(rng)), c = scale * (0.01 + u(rng)) * (i % 3 == 0 ? 1e-8 : 1.0);
    // |b| = sqrt(ac) (1 - d) for d from 1e-18 to 1: det from about 0 to ac, either side.
    const double d = std::pow(10.0, -18.0 * u(rng)) * (i % 4 == 0 ? -1.0 : 1.0);
    const double b = std::sqrt(a * c) * (1.0 - d) * (i % 2 ? 1.0 : -1.0);
    Mat2 m;
    m << a, b, b, c;
    const bool want = symEigenValues(m).l2 > 0.0;
    bool got = true;
    try {
      Metric::fromTensor(a, b, c);
    } catch (const Error&) {
      got = false;
    }
    ASSERT_EQ(got, want) << "a " << a << " b " << b << " c " << c;
    (got ? accepted : refused)++;
  }
  EXPECT_GT(accepted, 1000);
  EXPECT_GT(refused, 1000);
}

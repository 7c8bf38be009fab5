// The lazy minimum of control spaces (MinimumControlSpace): exact at every point, for
// any mix of structures and analytic fields.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "anisomesh/controlspace/background_mesh_control_space.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/minimum_control_space.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/error.h"
#include "controlspace_test_util.h"

using namespace anisomesh;

namespace {

using anisomesh::test_util::box;

ContinuousInsertionOptions minimumInsertion() {
  ContinuousInsertionOptions c;
  c.threshold = 0.3;
  c.sampleThreshold = 0.05;
  return c;
}

// Two crossing anisotropic fields with different orientations.
Metric fieldA(const Vec2& p) { return Metric::fromSizes(0.4, 0.02 + 0.2 * p.x(), 0.1 - 0.05 * p.y()); }
Metric fieldB(const Vec2& p) { return Metric::fromSizes(-0.2, 0.05, 0.005 + 0.3 * std::abs(p.x() - 0.6)); }
Metric fieldC(const Vec2& p) { return Metric::fromSizes(1.1 * p.y(), 0.01 + 0.05 * (p - Vec2(0.3, 0.7)).norm(), 0.08); }

// kind 0: analytic, 1: quadtree, 2: background mesh - of field f.
std::shared_ptr<const ControlSpace> makeInput(int kind, const MetricFunction& f) {
  if (kind == 0) return std::make_shared<AnalyticControlSpace>(box(0, 0, 1, 1), f);
  if (kind == 1) {
    QuadtreeOptions o;
    o.maxLevel = 7;
    auto cs = std::make_shared<QuadtreeControlSpace>(box(0, 0, 1, 1), o);
    insertMetricFunction(*cs, f, minimumInsertion());
    return cs;
  }
  BackgroundMeshOptions o;
  o.maxLevel = 7;
  auto cs = std::make_shared<BackgroundMeshControlSpace>(box(0, 0, 1, 1), o);
  insertMetricFunction(*cs, f, minimumInsertion());
  return cs;
}

Vec2 angleDirection(double a) { return {std::cos(a), std::sin(a)}; }

// The result's size is at most the input's in 32 directions (within rounding).
void expectInside(const Metric& r, const Metric& input, const Vec2& p) {
  for (int d = 0; d < 32; ++d) {
    const Vec2 v = angleDirection(d * M_PI / 32);
    ASSERT_LE(r.sizeAlong(v), input.sizeAlong(v) * (1 + 1e-9)) << p.transpose() << " direction " << d;
  }
}

}  // namespace

TEST(ControlSpaceMinimumLazy, InsideBothInputsAndEqualToTheSmallerAtRandomPoints) {
  // Every pair of (analytic, quadtree, background mesh) inputs of two crossing fields.
  for (int k1 : {0, 1, 2})
    for (int k2 : {0, 1, 2}) {
      const auto a = makeInput(k1, fieldA), b = makeInput(k2, fieldB);
      const MinimumControlSpace minimum({a, b});
      std::mt19937 rng(11 + 3 * k1 + k2);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      int aSmaller = 0, bSmaller = 0, crossing = 0;
      for (int k = 0; k < 10000; ++k) {
        const Vec2 p(u(rng), u(rng));
        const Metric r = minimum.metricAt(p), ma = a->metricAt(p), mb = b->metricAt(p);
        expectInside(r, ma, p);
        expectInside(r, mb, p);
        if (::testing::Test::HasFatalFailure()) return;
        // Where one input is smaller in every direction, the result is that input.
        if (metricInside(ma, mb)) {
          ++aSmaller;
          ASSERT_EQ(r.transform(), ma.transform()) << p.transpose();
        } else if (metricInside(mb, ma)) {
          ++bSmaller;
          ASSERT_EQ(r.transform(), mb.transform()) << p.transpose();
        } else {
          ++crossing;
          // Neither contains the other: the result is strictly smaller than each somewhere.
          EXPECT_GT(difference(r, ma), 1e-12);
          EXPECT_GT(difference(r, mb), 1e-12);
        }
      }
      // The fields are chosen so that all three cases occur.
      EXPECT_GT(aSmaller, 100) << k1 << k2;
      EXPECT_GT(bSmaller, 100) << k1 << k2;
      EXPECT_GT(crossing, 100) << k1 << k2;
    }
}

TEST(ControlSpaceMinimumLazy, ThreeInputsAndAnInputSmallerEverywhere) {
  const auto q = makeInput(1, fieldA), bg = makeInput(2, fieldB), an = makeInput(0, fieldC);
  // The finest field scaled down: smaller than the others in every direction everywhere.
  const auto tiny = std::make_shared<AnalyticControlSpace>(
      box(0, 0, 1, 1), [](const Vec2& p) { return intersect(intersect(fieldA(p), fieldB(p)), fieldC(p)).scaled(0.5); });
  const MinimumControlSpace three({q, bg, an});
  const MinimumControlSpace four({q, tiny, bg, an});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 10000; ++k) {
    const Vec2 p(u(rng), u(rng));
    const Metric r = three.metricAt(p);
    for (const auto& in : three.inputs()) expectInside(r, in->metricAt(p), p);
    if (::testing::Test::HasFatalFailure()) return;
    const Metric t = tiny->metricAt(p);
    ASSERT_EQ(four.metricAt(p).transform(), t.transform()) << p.transpose();
  }
}

TEST(ControlSpaceMinimumLazy, BoundsParameterizationAndErrors) {
  const auto a = std::make_shared<UniformControlSpace>(box(0, 0, 2, 1), Metric::isotropic(0.1));
  const auto b = std::make_shared<UniformControlSpace>(box(1, -1, 3, 0.5), Metric::fromSizes(0.2, 0.05, 0.3));
  const MinimumControlSpace m({a, b});
  EXPECT_EQ(m.bounds().lo, Vec2(1, 0));
  EXPECT_EQ(m.bounds().hi, Vec2(2, 0.5));
  EXPECT_EQ(m.parameterizationAt(Vec2(1.5, 0.2)), Mat2::Identity());
  const MetricSizes s = m.metricAt(Vec2(1.5, 0.2)).sizes();
  EXPECT_NEAR(s.h1, 0.05, 1e-12);
  EXPECT_NEAR(s.h2, 0.1, 1e-12);
  auto code = [](std::vector<std::shared_ptr<const ControlSpace>> in) {
    try {
      MinimumControlSpace bad(std::move(in));
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Internal;
  };
  EXPECT_EQ(code({}), ErrorCode::InvalidArgument);
  EXPECT_EQ(code({a, nullptr}), ErrorCode::InvalidArgument);
  const auto far = std::make_shared<UniformControlSpace>(box(5, 5, 6, 6), Metric::isotropic(0.1));
  EXPECT_EQ(code({a, far}), ErrorCode::InvalidDomain);
}

// Folding pairwise with minimumOf (the npm package's minimumControlSpace(a, b, c)) gives the
// k-input minimum exactly, not the pairwise intersections (intersection is not associative).
TEST(ControlSpaceMinimumLazy, PairwiseFoldIsTheKInputMinimum) {
  const auto q = makeInput(1, fieldA), bg = makeInput(2, fieldB), an = makeInput(0, fieldC);
  const auto folded = minimumOf(minimumOf(q, bg), an);
  const auto* m = dynamic_cast<const MinimumControlSpace*>(folded.get());
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->inputs().size(), 3u);
  const MinimumControlSpace three({q, bg, an});
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const Vec2 p(u(rng), u(rng));
    ASSERT_EQ(folded->metricAt(p).transform(), three.metricAt(p).transform()) << p.transpose();
  }
}

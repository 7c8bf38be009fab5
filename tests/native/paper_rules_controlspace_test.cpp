// The paper's control-space rules, each pinned by the figure the paper gives (section 2.2
// source weights, section 2.5 gradation: a_max, s, the pairwise rule; section 4: eq. 11
// weights with the epsilon shortcut, the query cache's closeness in the metric). The
// expected values are computed here from the paper's formulas, not from the code's
// helpers, so that changing a rule in the code fails a test.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "anisomesh/controlspace/background_mesh_control_space.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/controlspace/query_cache.h"

using namespace anisomesh;

namespace {

Box2 rulesUnitBox() { return Box2{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}; }

// Index of the node at p (exactly), -1 when none.
int nodeAt(const AdaptiveControlSpace& cs, const Vec2& p) {
  for (int i = 0; i < cs.nodeCount(); ++i)
    if ((cs.nodePosition(i) - p).norm() < 1e-12) return i;
  return -1;
}

// Counts the queries that reach it.
class CountingControlSpace : public ControlSpace {
 public:
  explicit CountingControlSpace(MetricFunction f) : f_(std::move(f)) {}
  Metric metricAt(const Vec2& p) const override {
    ++queries;
    return f_(p);
  }
  Box2 bounds() const override { return rulesUnitBox(); }
  mutable int queries = 0;

 private:
  MetricFunction f_;
};

}  // namespace

// Eq. 4: a_max = 2 (dr - 1) / (dr + 1).
TEST(PaperRulesGradation, SlopeIsTwoDrMinusOneOverDrPlusOne) {
  for (double dr : {1.0, 1.5, 2.0, 3.0, 8.0, 100.0})
    EXPECT_NEAR(gradationSlope(dr), 2.0 * (dr - 1.0) / (dr + 1.0), 1e-15) << dr;
  EXPECT_DOUBLE_EQ(gradationSlope(2.0), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(gradationSlope(8.0), 14.0 / 9.0);
}

// Eq. 7 at a = a_max: s = 1 + a_max d / h_i with h_i the size of M_i along PiPj; the
// limited M_j (eq. 9) then asks for h_i + a_max d along the edge, and s scales every
// size of M_i (also across the edge).
TEST(PaperRulesGradation, SFactorUsesTheSizeAlongTheEdge) {
  const double a = gradationSlope(2.0);
  // Isotropic: size along the edge h_i + a d.
  {
    const Metric mi = Metric::isotropic(0.1);
    Metric mj = Metric::isotropic(10.0);
    ASSERT_TRUE(limitGradation(mi, {0.0, 0.0}, mj, {1.0, 0.0}, a));
    EXPECT_NEAR(mj.sizeAlong({1.0, 0.0}), 0.1 + a * 1.0, 1e-12);
    EXPECT_NEAR(mj.sizeAlong({0.0, 1.0}), 0.1 + a * 1.0, 1e-12);
  }
  // Anisotropic M_i (0.1 along x, 0.5 along y), edge along y of length d = 0.3:
  // h_i = 0.5, s = 1 + a 0.3 / 0.5; M_j = min(iso 10, s M_i) has sizes 0.1 s, 0.5 s.
  {
    const Metric mi = Metric::fromSizes(0.0, 0.1, 0.5);
    Metric mj = Metric::isotropic(10.0);
    ASSERT_TRUE(limitGradation(mi, {0.0, 0.0}, mj, {0.0, 0.3}, a));
    const double s = 1.0 + a * 0.3 / 0.5;
    EXPECT_NEAR(mj.sizeAlong({0.0, 1.0}), 0.5 * s, 1e-12);
    EXPECT_NEAR(mj.sizeAlong({1.0, 0.0}), 0.1 * s, 1e-12);
  }
}

// Eqs. 8, 9: M_j = min(M_j, s M_i), the metric intersection: what M_j asks finer than
// s M_i is kept (anisotropy), and a M_j already inside s M_i is left alone.
TEST(PaperRulesGradation, PairwiseRuleIsTheMinimum) {
  const double a = gradationSlope(2.0);
  const Metric mi = Metric::isotropic(0.01);
  // Coarse along the edge, very fine across it: only the size along the edge shrinks.
  Metric mj = Metric::fromSizes(0.0, 10.0, 0.001);
  ASSERT_TRUE(limitGradation(mi, {0.0, 0.0}, mj, {0.5, 0.0}, a));
  EXPECT_NEAR(mj.sizeAlong({1.0, 0.0}), 0.01 + a * 0.5, 1e-9);
  EXPECT_NEAR(mj.sizeAlong({0.0, 1.0}), 0.001, 1e-12);
  // Already finer than s M_i: unchanged.
  Metric fine = Metric::isotropic(0.005);
  EXPECT_FALSE(limitGradation(mi, {0.0, 0.0}, fine, {0.5, 0.0}, a));
  EXPECT_EQ(fine.transform(), Metric::isotropic(0.005).transform());
}

// Global smoothing applies the pairwise rule both ways along the structure's edges: from
// one fine node in the middle of a coarse grid, the size grows by a_max per unit length
// along the grid lines on both sides (eqs. 8 and 9), for dr = 2 and dr = 8.
TEST(PaperRulesGradation, SmoothingGrowsSizesBySlopeOnBothSides) {
  for (double dr : {2.0, 8.0}) {
    QuadtreeOptions o;
    o.initialLevel = 4;  // 16 x 16 cells, h = 1/16
    o.maxLevel = 4;
    o.initialMetric = Metric::isotropic(1.0);
    QuadtreeControlSpace cs(rulesUnitBox(), o);
    const int c = nodeAt(cs, {0.5, 0.5});
    ASSERT_GE(c, 0);
    const double h0 = 0.01;
    cs.setNodeMetric(c, Metric::isotropic(h0));
    GradationOptions g;
    g.ratio = dr;
    EXPECT_GT(smoothGradation(cs, g), 0);
    const double amax = 2.0 * (dr - 1.0) / (dr + 1.0);
    for (int k = 1; k <= 8; ++k)
      for (double side : {-1.0, 1.0}) {
        const double d = k / 16.0;
        const int j = nodeAt(cs, {0.5 + side * d, 0.5});
        ASSERT_GE(j, 0);
        EXPECT_NEAR(cs.nodeMetric(j).sizeAlong({1.0, 0.0}), std::min(1.0, h0 + amax * d), 1e-9)
            << "dr " << dr << " k " << k << " side " << side;
      }
  }
}

// Section 2.2: a free node reached by discrete sources takes their weighted average in Mt
// with weights 1 / (max(d - r, 0) + target / 4)^2 (d: distance to the source, r: its
// radius, target = max(r, h_min(M)) * sizeFactor: equal inside the radius, decaying
// outside).
TEST(PaperRulesSources, NodeTakesTheDistanceWeightedAverage) {
  QuadtreeOptions o;
  o.initialLevel = 3;
  o.maxLevel = 3;  // no refinement: the nodes stay where they are
  QuadtreeControlSpace cs(rulesUnitBox(), o);
  const Vec2 p(0.5, 0.5);
  const int n = nodeAt(cs, p);
  ASSERT_GE(n, 0);
  struct S {
    Vec2 c;
    double r, h;
  };
  const std::vector<S> srcs = {{{0.55, 0.5}, 0.1, 0.2}, {{0.5, 0.72}, 0.1, 0.4}, {{0.3, 0.5}, 0.05, 0.3}};
  std::vector<MetricSource> sources;
  for (const S& s : srcs)
    sources.emplace_back(std::in_place_type<RadialSource>, RadialSource{s.c, Metric::isotropic(s.h), s.r});
  insertSources(cs, sources);
  const double minSize = cs.minElementSize();
  double sum = 0.0, wsum = 0.0;
  for (const S& s : srcs) {
    const double target = std::max(s.r, s.h);
    const double reach = std::max(target, minSize);
    const double d = (s.c - p).norm();
    ASSERT_LE(d, s.r + reach);  // every source reaches the node
    const double t = std::max(d - s.r, 0.0) + 0.25 * reach;
    sum += (1.0 / s.h) / (t * t);
    wsum += 1.0 / (t * t);
  }
  const double expected = wsum / sum;  // isotropic: Mt = (1/h) I averaged
  EXPECT_NEAR(cs.nodeMetric(n).sizeAlong({1.0, 0.0}), expected, 1e-12);
  EXPECT_NEAR(cs.nodeMetric(n).sizeAlong({0.0, 1.0}), expected, 1e-12);
  // The equal-weight average would differ clearly (the test can tell them apart).
  double plain = 0.0;
  for (const S& s : srcs) plain += 1.0 / s.h;
  EXPECT_GT(std::abs(3.0 / plain - expected), 1e-3);
}

// Eq. 11: Mt(Q) = sum w_i Mt(P_i) / sum w_i over the containing triangle's vertices with
// w_i = d(Q, P_i)^-2, and Mt(P_i) itself when d(Q, P_i) < epsilon.
TEST(PaperRulesBackground, InverseSquaredDistanceWeightsAndEpsilon) {
  BackgroundMeshOptions o;
  o.initialGrid = 1;  // two triangles: (0,0) (1,0) (1,1) and (0,0) (1,1) (0,1)
  o.maxLevel = 0;
  o.epsilon = 0.01;  // relative to the box diagonal
  BackgroundMeshControlSpace cs(rulesUnitBox(), o);
  ASSERT_EQ(cs.elementCount(), 2);
  const std::vector<Vec2> corners = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Metric> metrics = {Metric::fromSizes(0.3, 0.1, 0.4), Metric::isotropic(0.2),
                                       Metric::fromSizes(-0.7, 0.05, 0.3), Metric::isotropic(0.9)};
  std::vector<int> idx;
  for (size_t k = 0; k < corners.size(); ++k) {
    idx.push_back(nodeAt(cs, corners[k]));
    ASSERT_GE(idx.back(), 0);
    cs.setNodeMetric(idx.back(), metrics[k]);
  }
  // Inside triangle (0,0) (1,0) (1,1).
  for (const Vec2& q : {Vec2(0.6, 0.2), Vec2(0.9, 0.5), Vec2(0.3, 0.1)}) {
    Mat2 sum = Mat2::Zero();
    double wsum = 0.0;
    for (int k : {0, 1, 2}) {
      const double w = 1.0 / (q - corners[k]).squaredNorm();
      sum += w * metrics[k].transform();
      wsum += w;
    }
    const Mat2 expected = sum / wsum;
    EXPECT_LT((cs.metricAt(q).transform() - expected).norm(), 1e-12 * expected.norm()) << q.transpose();
  }
  // Within epsilon (0.01 * sqrt 2) of a vertex: that vertex's metric exactly.
  const Vec2 nearCorner(1.0 - 0.009, 0.001);
  EXPECT_EQ(cs.metricAt(nearCorner).transform(), metrics[1].transform());
  // Just outside epsilon: the blend (differs from the vertex's metric).
  const Vec2 outside(1.0 - 0.02, 0.0);
  EXPECT_GT((cs.metricAt(outside).transform() - metrics[1].transform()).norm(), 1e-6);
}

// Section 4: the cache reuses the last metric when the new point is close to the last
// query point measured in the last metric, |Mt_last (p - p_last)| < tolerance, not in
// plain distance.
TEST(PaperRulesQueryCache, ClosenessIsMeasuredInTheMetric) {
  // 0.01 along x, 1 along y: metric distance = 100 dx along x, dy along y.
  CountingControlSpace inner([](const Vec2& p) { return Metric::fromSizes(0.0, 0.01 + 0.001 * p.x(), 1.0); });
  QueryCacheOptions o;
  o.tolerance = 0.05;
  CachedControlSpace cache(inner, o);
  cache.metricAt({0.5, 0.5});
  EXPECT_EQ(inner.queries, 1);
  // 0.04 away along y: metric distance 0.04 < 0.05, a hit although plain distance is 0.04.
  cache.metricAt({0.5, 0.54});
  EXPECT_EQ(inner.queries, 1);
  EXPECT_EQ(cache.hits(), 1);
  // 0.002 away along x: plain distance 20 times smaller, metric distance ~0.2: a miss.
  cache.metricAt({0.502, 0.5});
  EXPECT_EQ(inner.queries, 2);
  // The miss answered with the inner metric at the new point.
  EXPECT_EQ(cache.metricAt({0.9, 0.9}).transform(), inner.metricAt({0.9, 0.9}).transform());
  // Distance just below / above the tolerance in the metric of the last point.
  const Metric last = inner.metricAt({0.9, 0.9});
  const int before = inner.queries;
  const double hx = last.sizeAlong({1.0, 0.0});
  cache.metricAt({0.9 + 0.049 * hx, 0.9});
  EXPECT_EQ(inner.queries, before);
  cache.metricAt({0.9 + 0.051 * hx, 0.9});
  EXPECT_EQ(inner.queries, before + 1);
}

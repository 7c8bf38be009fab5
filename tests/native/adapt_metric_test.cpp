// Metrics from fields, solution transfer and the adaptation loop: Lp complexity follows
// the requested N over the loop, transfer reproduces linear fields, documented results
// and coded errors for bad input, the control space composes by the minimum.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "adapt_test_util.h"
#include "anisomesh/adapt/adaptation_loop.h"
#include "anisomesh/adapt/solution_transfer.h"
#include "anisomesh/controlspace/minimum_control_space.h"
#include "anisomesh/core/error.h"

using namespace anisomesh;
using namespace adapttest;

namespace {

ErrorCode codeOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  return ErrorCode::Internal;
}

double layer(const Vec2& p) { return std::tanh(40 * (p.y() - 0.5 - 0.25 * std::sin(2 * M_PI * p.x()))); }

}  // namespace

TEST(SolutionTransfer, ReproducesLinearFieldsExactly) {
  const Mesh from = gridMesh(9, 0.5), to = remeshedSquare(Metric::fromSizes(0.3, 0.02, 0.1));
  std::vector<double> lin, other;
  for (const Vec3& p : from.points) lin.push_back(3.0 - 2.0 * p.x() + 5.0 * p.y()), other.push_back(p.x() * p.y());
  const auto out = transferFields(from, {lin, other}, to);
  ASSERT_EQ(out.size(), 2u);
  ASSERT_EQ(out[0].size(), to.points.size());
  double worst = 0;
  for (size_t i = 0; i < to.points.size(); ++i)
    worst = std::max(worst, std::abs(out[0][i] - (3.0 - 2.0 * to.points[i].x() + 5.0 * to.points[i].y())));
  EXPECT_LT(worst, 1e-12);
  // Outside the old mesh: the value at the nearest point of it (no extrapolation).
  Mesh outside;
  outside.points = {Vec3(1.5, 0.5, 0.0), Vec3(-1.0, -1.0, 0.0)};
  const auto o = transferFields(from, {lin}, outside);
  EXPECT_NEAR(o[0][0], 3.0 - 2.0 * 1.0 + 5.0 * 0.5, 1e-12);
  EXPECT_NEAR(o[0][1], 3.0, 1e-12);
}

TEST(FieldMetric, ConstantAndLinearFieldsGiveHmaxEverywhere) {
  const Mesh m = gridMesh(8, 0.4);
  FieldMetricOptions o;
  o.targetVertices = 500;
  o.hmax = 0.3;
  std::vector<double> lin;
  for (const Vec3& p : m.points) lin.push_back(1e3 + 2.0 * p.x() - p.y());
  for (const auto& f : {std::vector<double>(m.points.size(), 4.0), lin}) {
    for (double err : {0.0, 0.01}) {
      FieldMetricOptions oo = o;
      if (err > 0) oo.targetVertices = 0, oo.err = err;
      const FieldMetric fm = metricFromFields(m, {f}, oo);
      for (const Metric& mt : fm.metrics) {
        const MetricSizes s = mt.sizes();
        EXPECT_NEAR(s.h1, 0.3, 1e-12);
        EXPECT_NEAR(s.h2, 0.3, 1e-12);
      }
    }
  }
  // ... and the loop meshes it (hmax everywhere), no crash.
  AdaptOptions a;
  a.metric = o;
  a.iterations = 1;
  const AdaptResult r = adaptToFields(m, {std::vector<double>(m.points.size(), 4.0)}, a);
  EXPECT_GT(r.mesh.triangles.size(), 10u);
  EXPECT_LT(r.mesh.vertexCount(), 60);
}

TEST(FieldMetric, TargetComplexityAfterClampsAndBudget) {
  const Mesh m = remeshedSquare(Metric::isotropic(0.02));
  std::vector<double> f;
  for (const Vec3& p : m.points) f.push_back(layer(p.head<2>()));
  for (ErrorNorm norm : {ErrorNorm::L1, ErrorNorm::L2, ErrorNorm::Linf}) {
    FieldMetricOptions o;
    o.targetVertices = 3000;
    o.norm = norm;
    o.hmax = 0.1;
    o.hmin = 1e-4;
    const FieldMetric fm = metricFromFields(m, {f}, o);
    EXPECT_NEAR(fm.expectedVertices, 3000, 3000 * 1e-6);
    EXPECT_NEAR(metricComplexity(m, fm.metrics), fm.complexity, 1e-9 * fm.complexity);
    double worstRatio = 0;
    for (const Metric& mt : fm.metrics) {
      const MetricSizes s = mt.sizes();
      EXPECT_GE(s.h1, o.hmin * (1 - 1e-12));
      EXPECT_LE(s.h2, o.hmax * (1 + 1e-12));
      worstRatio = std::max(worstRatio, s.h2 / s.h1);
    }
    EXPECT_LE(worstRatio, o.anisomax * (1 + 1e-9));
    EXPECT_GT(worstRatio, 5);  // the layer gives anisotropic metrics
  }
  FieldMetricOptions o;
  o.targetVertices = 1e6;
  o.maxElements = 100000;
  EXPECT_EQ(codeOf([&] { metricFromFields(m, {f}, o); }), ErrorCode::ElementBudgetExceeded);
  o.targetVertices = 0;
  o.err = 1e-9;
  o.hmin = 1e-7;
  EXPECT_EQ(codeOf([&] { metricFromFields(m, {f}, o); }), ErrorCode::ElementBudgetExceeded);
  o.err = 0.01;
  o.targetVertices = 100;
  EXPECT_EQ(codeOf([&] { metricFromFields(m, {f}, o); }), ErrorCode::InvalidArgument);  // both
  o.err = 0;
  o.targetVertices = 0;
  EXPECT_EQ(codeOf([&] { metricFromFields(m, {f}, o); }), ErrorCode::InvalidArgument);  // neither
  o.targetVertices = 100;
  o.anisomax = 0.5;
  EXPECT_EQ(codeOf([&] { metricFromFields(m, {f}, o); }), ErrorCode::InvalidArgument);
  o.anisomax = 10;
  o.hmin = 1;
  o.hmax = 0.1;
  EXPECT_EQ(codeOf([&] { metricFromFields(m, {f}, o); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(codeOf([&] { metricFromFields(m, {}, FieldMetricOptions{}); }), ErrorCode::InvalidArgument);
}

// Over the loop, the adapted meshes have N vertices within 10% (the metric's complexity
// is N sqrt(3)/2 exactly), for the three norms.
TEST(AdaptationLoop, VertexCountFollowsTargetComplexity) {
  const Mesh start = remeshedSquare(Metric::isotropic(0.04));
  for (ErrorNorm norm : {ErrorNorm::L1, ErrorNorm::L2, ErrorNorm::Linf}) {
    AdaptOptions o;
    o.metric.targetVertices = 2000;
    o.metric.norm = norm;
    o.metric.hmax = 0.2;
    o.iterations = 4;
    const AdaptResult r = adaptToFunctions(start, {layer}, o);
    ASSERT_EQ(r.iterations.size(), 4u);
    for (size_t k = 0; k < r.iterations.size(); ++k) {
      const AdaptIteration& it = r.iterations[k];
      std::cout << "norm " << int(norm) << " iteration " << k << ": vertices " << it.vertices << " triangles "
                << it.triangles << " expected " << it.expectedVertices << " Linf " << it.errorLinf << " L2 "
                << it.errorL2 << " estimate " << it.estimatedError << "\n";
      EXPECT_NEAR(it.vertices, 2000, 200) << "iteration " << k;
    }
    EXPECT_EQ(r.fields[0].size(), r.mesh.points.size());
  }
}

// Error-level mode: the mesh reaches about the requested L-inf error, and halving err
// about doubles the vertices (complexity ~ 1/err in 2D).
TEST(AdaptationLoop, ErrorLevelIsReached) {
  const Mesh start = remeshedSquare(Metric::isotropic(0.04));
  int vertices[2];
  for (int k = 0; k < 2; ++k) {
    AdaptOptions o;
    o.metric.err = k == 0 ? 0.02 : 0.01;
    o.metric.hmax = 0.2;
    o.iterations = 3;
    const AdaptResult r = adaptToFunctions(start, {layer}, o);
    const AdaptIteration& it = r.iterations.back();
    std::cout << "err " << o.metric.err << ": vertices " << it.vertices << " Linf " << it.errorLinf << " estimate "
              << it.estimatedError << "\n";
    EXPECT_LT(it.errorLinf, 2 * o.metric.err);
    EXPECT_GT(it.errorLinf, 0.3 * o.metric.err);
    vertices[k] = it.vertices;
  }
  EXPECT_NEAR(double(vertices[1]) / vertices[0], 2.0, 0.4);
}

// The field's control space is a ControlSpace: the section 2.4 minimum with a user source
// (here a uniform size) is inside both.
TEST(AdaptationLoop, ControlSpaceComposesByMinimum) {
  const Mesh m = remeshedSquare(Metric::isotropic(0.03));
  std::vector<double> f;
  for (const Vec3& p : m.points) f.push_back(layer(p.head<2>()));
  FieldMetricOptions fo;
  fo.targetVertices = 1000;
  const FieldMetric fm = metricFromFields(m, {f}, fo);
  std::shared_ptr<const ControlSpace> field = fieldControlSpace(m, fm);
  auto user = std::make_shared<UniformControlSpace>(field->bounds(), Metric::isotropic(0.05));
  const MinimumControlSpace both({field, user});
  for (double x = 0.05; x < 1; x += 0.1)
    for (double y = 0.05; y < 1; y += 0.1) {
      const Metric mm = both.metricAt({x, y}), mf = field->metricAt({x, y});
      for (double a = 0; a < 3.14; a += 0.1) {
        const Vec2 dir(std::cos(a), std::sin(a));
        EXPECT_LE(mm.sizeAlong(dir), mf.sizeAlong(dir) * (1 + 1e-9));
        EXPECT_LE(mm.sizeAlong(dir), 0.05 * (1 + 1e-9));
      }
    }
}

TEST(AdaptationLoop, BadInputIsCoded) {
  const Mesh m = gridMesh(6);
  AdaptOptions o;
  o.metric.targetVertices = 200;
  EXPECT_EQ(codeOf([&] { adaptToFields(m, {std::vector<double>(3, 0.0)}, o); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(codeOf([&] { adaptToFields(m, {}, o); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(codeOf([&] { adaptToFunctions(m, {[](const Vec2& p) { return std::log(p.x()); }}, o); }),
            ErrorCode::InvalidArgument);  // log(0) at x = 0
  o.iterations = 0;
  EXPECT_EQ(codeOf([&] { adaptToFunctions(m, {layer}, o); }), ErrorCode::InvalidArgument);
  o.iterations = 1;
  o.hgrad = 0.5;
  EXPECT_EQ(codeOf([&] { adaptToFunctions(m, {layer}, o); }), ErrorCode::InvalidArgument);
  Mesh inverted = m;
  std::swap(inverted.triangles[0][1], inverted.triangles[0][2]);
  o.hgrad = 0;
  EXPECT_EQ(codeOf([&] { adaptToFunctions(inverted, {layer}, o); }), ErrorCode::InvalidDomain);
}

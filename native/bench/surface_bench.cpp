// Kernels of the surface area: the expression evaluator (value only and with exact
// second derivatives) and the curvature metric, all on the paper's surface p2.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "anisomesh/geometry/expression.h"
#include "anisomesh/geometry/surface.h"
#include "anisomesh/geometry/surface_metric.h"

using namespace anisomesh;

namespace {

const char* kP2 = "1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)";

// A fixed 64 x 64 grid of query points over [-10, 10]^2.
std::vector<Vec2> surfaceGrid() {
  std::vector<Vec2> pts;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) pts.emplace_back(-10 + 20.0 * i / 63, -10 + 20.0 * j / 63);
  return pts;
}

void BM_ExpressionP2Value(benchmark::State& state) {
  const Expression e = Expression::parse(kP2);
  const auto pts = surfaceGrid();
  size_t i = 0;
  for (auto _ : state) {
    const Vec2& p = pts[i++ & 4095];
    benchmark::DoNotOptimize(e.value(p.x(), p.y()));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ExpressionP2Value);

void BM_ExpressionP2Derivatives(benchmark::State& state) {
  const Expression e = Expression::parse(kP2);
  const auto pts = surfaceGrid();
  size_t i = 0;
  for (auto _ : state) {
    const Vec2& p = pts[i++ & 4095];
    benchmark::DoNotOptimize(e.evaluate(p.x(), p.y()));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ExpressionP2Derivatives);

// Hand-written p2 height with the same derivatives, as the floor the evaluator is compared to.
void BM_HandWrittenP2Derivatives(benchmark::State& state) {
  const auto pts = surfaceGrid();
  size_t i = 0;
  for (auto _ : state) {
    const Vec2& p = pts[i++ & 4095];
    const double u = p.x(), v = p.y();
    const double g = 1.5 * std::exp(-0.001 * (u * u + v * v));
    const double s = std::sin(2 * u), c = std::cos(2 * u), cv = std::cos(0.2 * v), sv = std::sin(0.2 * v);
    const double gu = -0.002 * u * g, gv = -0.002 * v * g;
    Dual2 r;
    r.f = g * s * cv;
    r.fu = (gu * s + 2 * g * c) * cv;
    r.fv = gv * s * cv - 0.2 * g * s * sv;
    r.fuu = ((-0.002 * g - 0.002 * u * gu) * s + 4 * gu * c - 4 * g * s) * cv;
    r.fuv = (-0.002 * u * gv * s + 2 * gv * c) * cv - 0.2 * (gu * s + 2 * g * c) * sv;
    r.fvv = (-0.002 * g - 0.002 * v * gv) * s * cv - 0.4 * gv * s * sv - 0.04 * g * s * cv;
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HandWrittenP2Derivatives);

void BM_SurfaceP2Derivatives(benchmark::State& state) {
  const auto p2 = paperP2();
  const auto pts = surfaceGrid();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(p2->derivatives(pts[i++ & 4095]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SurfaceP2Derivatives);

void BM_CurvatureMetricP2(benchmark::State& state) {
  const auto p2 = paperP2();
  const auto pts = surfaceGrid();
  SurfaceMetricOptions o;
  o.chordTolerance = 0.005;
  o.hmin = 0.01;
  o.hmax = 2.0;
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(parameterMetric(*p2, pts[i++ & 4095], o));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CurvatureMetricP2);

void BM_ControlSpaceMetricAtP2(benchmark::State& state) {
  SurfaceMetricOptions o;
  o.chordTolerance = 0.005;
  o.hmin = 0.01;
  o.hmax = 2.0;
  const SurfaceCurvatureControlSpace cs(paperP2(), o);
  const auto pts = surfaceGrid();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(cs.metricAt(pts[i++ & 4095]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ControlSpaceMetricAtP2);

}  // namespace

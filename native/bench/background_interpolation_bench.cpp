// Background mesh interpolation (section 4.2): eq. 11 inverse-squared-distance weights
// over the containing triangle's vertices (with the epsilon shortcut) against barycentric
// weights, on the same structure: query speed, and accuracy against the analytic field
// the structure was built from (relative error of Mt at 65536 random points).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "anisomesh/controlspace/background_mesh_control_space.h"
#include "anisomesh/controlspace/control_space_algorithms.h"

using namespace anisomesh;

namespace {

Box2 unitBox() { return Box2{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}; }

// 0: boundary layer (stretch 100 at y = 0.5); 1: smooth rotating anisotropic field.
Metric field(int f, const Vec2& p) {
  if (f == 0) return Metric::fromSizes(0.0, 0.1, 0.001 + 0.1 * std::abs(p.y() - 0.5));
  return Metric::fromSizes(3.0 * p.x() * p.y(), 0.01 + 0.05 * p.x(), 0.05 + 0.05 * std::sin(3.0 * p.y()));
}

// Same structure for both interpolations: refinement by node differences only (the
// sample check would depend on the interpolation), node values from the field.
std::unique_ptr<BackgroundMeshControlSpace> build(int f, BackgroundInterpolation interp) {
  BackgroundMeshOptions b;
  b.maxLevel = 12;
  b.interpolation = interp;
  auto cs = std::make_unique<BackgroundMeshControlSpace>(unitBox(), b);
  ContinuousInsertionOptions c;
  c.threshold = 0.1;
  c.checkSamples = false;
  insertMetricFunction(
      *cs, [f](const Vec2& p) { return field(f, p); }, c);
  return cs;
}

std::vector<Vec2> randomPoints() {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> pts(1 << 16);
  for (auto& q : pts) {
    const double x = u(rng);
    const double y = u(rng);
    q = Vec2(x, y);
  }
  return pts;
}

// Args: field (0 boundary layer, 1 rotating), interpolation (0 eq. 11, 1 barycentric).
void BM_BackgroundInterpolation(benchmark::State& state) {
  const int f = static_cast<int>(state.range(0));
  const auto interp =
      state.range(1) == 0 ? BackgroundInterpolation::InverseSquaredDistance : BackgroundInterpolation::Linear;
  const auto cs = build(f, interp);
  const std::vector<Vec2> pts = randomPoints();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(cs->metricAt(pts[i]));
    i = (i + 1) & (pts.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(interp == BackgroundInterpolation::Linear ? "barycentric" : "eq11-inverse-squared-distance");
  double sum = 0.0, worst = 0.0, sizeSum = 0.0, sizeWorst = 0.0;
  for (const Vec2& p : pts) {
    const Metric exact = field(f, p), got = cs->metricAt(p);
    const double e = (got.transform() - exact.transform()).norm() / exact.transform().norm();
    sum += e;
    worst = std::max(worst, e);
    // Largest relative error of the requested size over 8 directions.
    double s = 0.0;
    for (int k = 0; k < 8; ++k) {
      const Vec2 u(std::cos(k * 0.3927), std::sin(k * 0.3927));
      s = std::max(s, std::abs(got.sizeAlong(u) / exact.sizeAlong(u) - 1.0));
    }
    sizeSum += s;
    sizeWorst = std::max(sizeWorst, s);
  }
  state.counters["nodes"] = cs->nodeCount();
  state.counters["mt_err_mean"] = sum / pts.size();
  state.counters["mt_err_max"] = worst;
  state.counters["size_err_mean"] = sizeSum / pts.size();
  state.counters["size_err_max"] = sizeWorst;
}
BENCHMARK(BM_BackgroundInterpolation)->ArgNames({"field", "barycentric"})->ArgsProduct({{0, 1}, {0, 1}});

}  // namespace

// Kernels of the metric algebra: intersection and interpolation of Mt.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "anisomesh/metric/metric.h"

using namespace anisomesh;

namespace {

std::vector<Metric> randomMetrics(int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> a(-3.14, 3.14), h(1e-3, 1.0);
  std::vector<Metric> out;
  for (int i = 0; i < n; ++i) out.push_back(Metric::fromSizes(a(rng), h(rng), h(rng)));
  return out;
}

void BM_MetricIntersect(benchmark::State& state) {
  const auto ms = randomMetrics(1024);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(intersect(ms[i & 1023], ms[(i + 1) & 1023]));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MetricIntersect);

void BM_MetricInterpolate(benchmark::State& state) {
  const auto ms = randomMetrics(1024);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(interpolate(ms[i & 1023], ms[(i + 1) & 1023], 0.3));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MetricInterpolate);

}  // namespace

// Adaptation (issue #13): Hessian recovery throughput (vertices per second) on jittered
// grids, and one whole adaptation cycle (recovery, metric, control space, remeshing,
// re-sampling, error) towards N vertices for the curved tanh layer of examples/adaptation.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "anisomesh/adapt/adaptation_loop.h"
#include "anisomesh/adapt/hessian_recovery.h"

using namespace anisomesh;

namespace {

// An n x n grid of the unit square, interior vertices jittered by 0.3 cell (deterministic).
Mesh grid(int n) {
  Mesh m;
  std::uint64_t s = 7;
  auto rnd = [&s]() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(s >> 11) / double(1ULL << 53) - 0.5;
  };
  const double h = 1.0 / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool inner = i > 0 && i < n && j > 0 && j < n;
      m.points.emplace_back(i * h + (inner ? 0.3 * h * rnd() : 0.0), j * h + (inner ? 0.3 * h * rnd() : 0.0), 0.0);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
      m.triangleRefs.push_back(0);
      m.triangleRefs.push_back(0);
    }
  return m;
}

double layer(const Vec2& p) { return std::tanh(40 * (p.y() - 0.5 - 0.25 * std::sin(2 * M_PI * p.x()))); }

// range(0): grid cells per side (316: ~1e5 vertices, 1000: ~1e6).
void BM_HessianRecovery(benchmark::State& state) {
  const Mesh m = grid(int(state.range(0)));
  std::vector<double> f;
  for (const Vec3& p : m.points) f.push_back(layer(p.head<2>()));
  for (auto _ : state) benchmark::DoNotOptimize(recoverHessian(m, f));
  state.counters["vertices"] = double(m.vertexCount());
  state.counters["vertices_per_s"] =
      benchmark::Counter(double(m.vertexCount()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_HessianRecovery)->Arg(316)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

// One adaptation cycle from a uniform grid of about N vertices towards N vertices (L2).
void BM_AdaptCycle(benchmark::State& state) {
  const int n = int(state.range(0));
  const Mesh m = grid(int(std::lround(std::sqrt(double(n)))));
  AdaptOptions o;
  o.metric.targetVertices = n;
  o.metric.norm = ErrorNorm::L2;
  o.metric.hmax = 0.2;
  o.iterations = 1;
  int vertices = 0;
  for (auto _ : state) vertices = adaptToFunctions(m, {layer}, o).mesh.vertexCount();
  state.counters["vertices"] = vertices;
}
BENCHMARK(BM_AdaptCycle)->Arg(100000)->Arg(1000000)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

// Throughput of the planar metric mesher on an anisotropic boundary-layer case
// (unit square, layer along y = 0.5, aspect ratio 100), in triangles per second.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/mesh/planar_mesher.h"

using namespace anisomesh;

namespace {

// Boundary points of segment [a, b) at unit metric spacing (numerical integration).
void discretize(const Vec2& a, const Vec2& b, const ControlSpace& cs, BoundaryLoop& loop, int ref) {
  const int steps = 20000;
  std::vector<double> cum(steps + 1, 0.0);
  for (int i = 0; i < steps; ++i) {
    const Vec2 p0 = a + (b - a) * (double(i) / steps), p1 = a + (b - a) * (double(i + 1) / steps);
    cum[i + 1] = cum[i] + cs.metricAt(0.5 * (p0 + p1)).length(p1 - p0);
  }
  const int n = std::max(1, int(std::lround(cum[steps])));
  int j = 0;
  for (int k = 0; k < n; ++k) {
    const double s = cum[steps] * k / n;
    while (j < steps && cum[j + 1] < s) ++j;
    const double f = (s - cum[j]) / (cum[j + 1] - cum[j]);
    loop.points.push_back(a + (b - a) * ((j + f) / steps));
    loop.edgeRefs.push_back(ref);
  }
}

void BM_MeshBoundaryLayer(benchmark::State& state) {
  const double h = 1.0 / static_cast<double>(state.range(0));
  AnalyticControlSpace cs({{0, 0}, {1, 1}}, [h](const Vec2& p) {
    // Axis-aligned: Mt = diag(1/hx, 1/hy) directly (cheaper than fromSizes' validation).
    Mat2 mt = Mat2::Zero();
    mt(0, 0) = 1.0 / h;
    mt(1, 1) = 1.0 / std::min(h, 0.01 * h + 0.2 * std::fabs(p.y() - 0.5));
    return Metric::fromTransformUnchecked(mt);
  });
  BoundaryLoop loop;
  const Vec2 c[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) discretize(c[i], c[(i + 1) % 4], cs, loop, i + 1);
  const std::vector<BoundaryLoop> loops{loop};
  std::int64_t triangles = 0;
  MesherTimings timings;
  PlanarMesherOptions opt;
  opt.timings = &timings;
  for (auto _ : state) {
    const Mesh m = meshPlanarBoundary(loops, cs, opt);
    triangles += static_cast<std::int64_t>(m.triangles.size());
    benchmark::DoNotOptimize(m.triangles.data());
  }
  state.counters["triangles"] = benchmark::Counter(static_cast<double>(triangles) / state.iterations());
  state.counters["boundary_s"] = timings.boundary;
  state.counters["insertion_s"] = timings.insertion;
  state.counters["improvement_s"] = timings.improvement;
  state.counters["triangles/s"] = benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsRate);
}
// ~100k and ~1M triangles.
BENCHMARK(BM_MeshBoundaryLayer)->Arg(200)->Arg(690)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

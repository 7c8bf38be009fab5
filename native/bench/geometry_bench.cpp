// Geometry and I/O kernels: domain validation, contour discretization, Medit parsing.
#include <benchmark/benchmark.h>

#include <memory>

#include "anisomesh/boundary/discretize.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/pipeline/case_control_space.h"

using namespace anisomesh;

namespace {

Domain manyHoles(int side) {
  Domain d;
  const double s = side;
  d.outer.add(std::make_shared<PolylineCurve>(std::vector<Vec2>{{0, 0}, {s, 0}, {s, s}, {0, s}, {0, 0}}));
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      Contour c;
      c.add(std::make_shared<ArcCurve>(ArcCurve::circle({0.5 + i, 0.5 + j}, 0.3)));
      d.holes.push_back(c);
    }
  return d;
}

void BM_ValidateDomainHoles(benchmark::State& state) {
  const Domain d = manyHoles(int(state.range(0)));
  for (auto _ : state) validateDomain(d);
  state.SetItemsProcessed(state.iterations() * state.range(0) * state.range(0));
}
BENCHMARK(BM_ValidateDomainHoles)->Arg(10)->Arg(30);

void BM_DiscretizeGradedCase(benchmark::State& state) {
  const CaseSpec spec = parseCaseJson(R"({
    "domain": {"outer": [{"type": "polyline", "points": [[0,0],[10,0],[10,5],[0,5],[0,0]]}],
               "holes": [[{"type": "circle", "center": [5, 2.5], "radius": 0.5}]]},
    "controlSpace": {"hmax": 0.1, "gradation": 2},
    "sources": [{"type": "radial", "center": [5, 2.5], "metric": {"h1": 0.005}, "radius": 0.7},
                {"type": "analytic", "field": "boundary_layer", "p1": [0, 0], "p2": [10, 0], "h0": 0.001, "hTangent": 0.1, "thickness": 0.2}]})");
  const auto cs = buildCaseControlSpace(spec);
  size_t points = 0;
  for (auto _ : state) {
    const auto loops = discretizeDomain(spec.domain, *cs);
    points = loops[0].points.size() + loops[1].points.size();
    benchmark::DoNotOptimize(points);
  }
  state.counters["points"] = double(points);
}
BENCHMARK(BM_DiscretizeGradedCase);

void BM_ParseMedit(benchmark::State& state) {
  const int n = int(state.range(0));
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.points.push_back(Vec3(i * 0.01, j * 0.01, 0));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      m.triangles.push_back({a, a + 1, a + n + 2});
      m.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  const std::string text = writeMedit(m);
  for (auto _ : state) benchmark::DoNotOptimize(parseMedit(text).triangles.size());
  state.SetBytesProcessed(state.iterations() * int64_t(text.size()));
}
BENCHMARK(BM_ParseMedit)->Arg(300);

}  // namespace

// Metric queries at random points on the control space of an example case: the same
// structure that native/bench/case_queries.mjs queries through the npm package, so the
// two figures compare native and WebAssembly directly.
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "anisomesh/io/case_json.h"
#include "anisomesh/pipeline/case_control_space.h"

using namespace anisomesh;

namespace {

void BM_CaseControlSpaceQuery(benchmark::State& state, const std::string& file) {
  const CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + file);
  const auto cs = buildCaseControlSpace(spec);
  const Box2 b = cs->bounds();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(b.lo.x(), b.hi.x()), uy(b.lo.y(), b.hi.y());
  std::vector<Vec2> pts(1 << 16);
  for (auto& p : pts) {
    const double x = ux(rng);
    p = Vec2(x, uy(rng));
  }
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(cs->metricAt(pts[i]));
    i = (i + 1) & (pts.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["nodes"] = cs->nodeCount();
}
BENCHMARK_CAPTURE(BM_CaseControlSpaceQuery, boundary_layer, std::string("boundary_layer.json"));
BENCHMARK_CAPTURE(BM_CaseControlSpaceQuery, shear_layer, std::string("shear_layer.json"));

}  // namespace

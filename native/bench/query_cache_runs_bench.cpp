// Section 4 query cache on real runs: every planar example meshed (meshCase: contour
// discretization, section 3.2 rounds, final meshing) and a remesh of the boundary layer
// under its own metric, with the cache off (tolerance 0) and on (0.05, 0.1, 0.2, metric
// distance). Counters: wall time per run (CPU time beside it), hit rate, and the mesh
// quality measured against the uncached control space, so a win in time can be weighed
// against what the approximation costs.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "anisomesh/io/case_json.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/pipeline/pipeline.h"

using namespace anisomesh;

namespace {

const char* kExamples[] = {"boundary_layer.json",      "expression_field.json",    "fig6_rect_holes_nosmooth.json",
                           "fig7_rect_holes_dr2.json", "fig7_rect_holes_dr8.json", "point_source.json",
                           "shear_layer.json"};
const double kTolerances[] = {0.0, 0.05, 0.1, 0.2};

void report(benchmark::State& state, const Mesh& mesh, const ControlSpace& cs, const PipelineReport& r) {
  const QualityReport q = measureQuality(mesh, cs);
  state.counters["vertices"] = mesh.vertexCount();
  state.counters["q_mean"] = q.qualityMean;
  state.counters["q_min"] = q.qualityMin;
  state.counters["within_sqrt2"] = q.edgesWithinSqrt2;
  const double queries = double(r.cacheHits + r.cacheMisses);
  state.counters["hit_rate"] = queries > 0 ? r.cacheHits / queries : 0.0;
}

// Args: example index, tolerance index.
void BM_CaseRunWithQueryCache(benchmark::State& state) {
  const std::string name = kExamples[state.range(0)];
  CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + name);
  spec.controlSpace.queryCache = kTolerances[state.range(1)];
  Mesh mesh;
  PipelineReport r;
  std::unique_ptr<AdaptiveControlSpace> cs;
  for (auto _ : state) {
    r = PipelineReport{};
    mesh = meshCase(spec, &r, {}, &cs);
  }
  state.SetLabel(name + " tol " + std::to_string(kTolerances[state.range(1)]).substr(0, 4));
  report(state, mesh, *cs, r);
}
BENCHMARK(BM_CaseRunWithQueryCache)
    ->ArgNames({"example", "tol"})
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// Remesh of the boundary layer example under the metric of its own final control space.
void BM_RemeshWithQueryCache(benchmark::State& state) {
  const CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/boundary_layer.json");
  std::unique_ptr<AdaptiveControlSpace> source;
  const Mesh input = meshCase(spec, nullptr, {}, &source);
  std::vector<Metric> metrics;
  for (const Vec3& p : input.points) metrics.push_back(source->metricAt(p.head<2>()));
  RemeshOptions o;
  o.queryCache = kTolerances[state.range(0)];
  Mesh mesh;
  PipelineReport r;
  std::unique_ptr<AdaptiveControlSpace> cs;
  for (auto _ : state) {
    r = PipelineReport{};
    mesh = remesh(input, metrics, o, &r, &cs);
  }
  state.SetLabel("remesh boundary_layer tol " + std::to_string(kTolerances[state.range(0)]).substr(0, 4));
  report(state, mesh, *cs, r);
}
BENCHMARK(BM_RemeshWithQueryCache)
    ->ArgNames({"tol"})
    ->DenseRange(0, 3)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace

// Surface meshing throughput on the paper's p2 patch with holes (fig. 10), the chord
// tolerance scaled so the mesh has 100k+ triangles. Reports triangles per second and the
// time spent in curvature evaluation (building the control space) and in control-space
// queries (contour discretization and meshing), from the run's own counters.
#include <benchmark/benchmark.h>

#include <memory>

#include "anisomesh/geometry/surface.h"
#include "anisomesh/surface/surface_mesh.h"

using namespace anisomesh;

namespace {

SurfacePatch p2WithHoles() {
  SurfacePatch p;
  p.name = "p2";
  p.surface = paperP2();
  const Box2 b = p.surface->domain();
  const Vec2 c1(b.hi.x(), b.lo.y()), c3(b.lo.x(), b.hi.y());
  p.domain.outer.add(std::make_shared<LineCurve>(b.lo, c1, 1));
  p.domain.outer.add(std::make_shared<LineCurve>(c1, b.hi, 2));
  p.domain.outer.add(std::make_shared<LineCurve>(b.hi, c3, 3));
  p.domain.outer.add(std::make_shared<LineCurve>(c3, b.lo, 4));
  for (const auto& h :
       {std::make_pair(Vec2(-4, 3), 1.5), std::make_pair(Vec2(3, -4), 2.0), std::make_pair(Vec2(5, 5), 1.0)}) {
    Contour hole;
    hole.add(std::make_shared<ArcCurve>(ArcCurve::circle(h.first, h.second, 5)));
    p.domain.holes.push_back(hole);
  }
  return p;
}

void BM_SurfaceMeshP2Holes(benchmark::State& state) {
  const SurfacePatch patch = p2WithHoles();
  SurfaceMeshOptions o;
  o.metric.chordTolerance = 0.00045;
  o.metric.hmin = 0.002;
  o.metric.hmax = 0.2;
  o.metric.maxAspectRatio = 6.0;
  o.gradation = 2.0;
  o.measureQuality = false;
  SurfaceMeshReport r;
  for (auto _ : state) {
    const Mesh m = meshSurfacePatch(patch, o, &r);
    benchmark::DoNotOptimize(m.triangles.data());
  }
  state.counters["triangles"] = r.triangles;
  state.counters["triangles_per_s"] =
      benchmark::Counter(double(r.triangles) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["curvature_evals"] = double(r.curvatureEvaluations);
  state.counters["curvature_s"] = r.curvatureSeconds;
  state.counters["cs_queries"] = double(r.controlSpaceQueries);
  state.counters["cs_query_s"] = r.controlSpaceSeconds;
  state.counters["total_s"] = r.secondsTotal;
}
BENCHMARK(BM_SurfaceMeshP2Holes)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

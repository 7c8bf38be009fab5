// Control space kernels: metric queries (cache off/on), construction from discrete
// sources, gradation smoothing, memory per control node.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "anisomesh/controlspace/background_mesh_control_space.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/controlspace/query_cache.h"

using namespace anisomesh;

namespace {

Box2 csUnitBox() { return Box2{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}; }

Metric boundaryLayer(const Vec2& p) { return Metric::fromSizes(0.0, 0.1, 0.001 + 0.1 * std::abs(p.y() - 0.5)); }

ContinuousInsertionOptions insertion() {
  ContinuousInsertionOptions c;
  c.threshold = 0.3;
  c.sampleThreshold = 0.05;
  return c;
}

// The structures queried: the boundary layer field, built once.
struct Spaces {
  AnalyticControlSpace analytic{csUnitBox(), boundaryLayer};
  std::unique_ptr<QuadtreeControlSpace> bilinear, serendipity;
  std::unique_ptr<BackgroundMeshControlSpace> background;
  Spaces() {
    QuadtreeOptions q;
    q.maxLevel = 10;
    bilinear = std::make_unique<QuadtreeControlSpace>(csUnitBox(), q);
    insertMetricFunction(*bilinear, boundaryLayer, insertion());
    q.interpolation = QuadtreeInterpolation::Serendipity;
    serendipity = std::make_unique<QuadtreeControlSpace>(csUnitBox(), q);
    insertMetricFunction(*serendipity, boundaryLayer, insertion());
    BackgroundMeshOptions b;
    b.maxLevel = 12;
    background = std::make_unique<BackgroundMeshControlSpace>(csUnitBox(), b);
    insertMetricFunction(*background, boundaryLayer, insertion());
  }
};

const Spaces& spaces() {
  static const Spaces s;
  return s;
}

// Query points: random in the box (pattern 0) or a path of small steps (pattern 1, the
// locality a mesher has when it walks along a front).
std::vector<Vec2> queryPoints(int pattern) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0), step(-2e-5, 2e-5);
  std::vector<Vec2> pts(1 << 16);
  Vec2 p(0.3, 0.5);
  for (auto& q : pts) {
    if (pattern == 0) {
      const double x = u(rng);
      const double y = u(rng);
      q = Vec2(x, y);
    } else {
      const double dx = step(rng);
      const double dy = step(rng);
      p = (p + Vec2(dx, dy)).cwiseMax(Vec2(0.0, 0.0)).cwiseMin(Vec2(1.0, 1.0));
      q = p;
    }
  }
  return pts;
}

// Args: kind (0 analytic, 1 quadtree bilinear, 2 quadtree serendipity, 3 background
// mesh), cache (0/1), pattern (0 random, 1 path).
void BM_ControlSpaceQuery(benchmark::State& state) {
  const Spaces& s = spaces();
  const int kind = static_cast<int>(state.range(0));
  const ControlSpace* cs = kind == 0   ? static_cast<const ControlSpace*>(&s.analytic)
                           : kind == 1 ? static_cast<const ControlSpace*>(s.bilinear.get())
                           : kind == 2 ? static_cast<const ControlSpace*>(s.serendipity.get())
                                       : static_cast<const ControlSpace*>(s.background.get());
  const char* names[4] = {"analytic", "quadtree-bilinear", "quadtree-serendipity", "background-mesh"};
  std::unique_ptr<CachedControlSpace> cached;
  if (state.range(1)) cached = std::make_unique<CachedControlSpace>(*cs);
  const ControlSpace& q = cached ? static_cast<const ControlSpace&>(*cached) : *cs;
  const std::vector<Vec2> pts = queryPoints(static_cast<int>(state.range(2)));
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(q.metricAt(pts[i]));
    i = (i + 1) & (pts.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(names[kind]);
  if (const auto* a = dynamic_cast<const AdaptiveControlSpace*>(cs)) {
    state.counters["nodes"] = a->nodeCount();
    state.counters["elements"] = a->elementCount();
  }
  if (kind == 1 || kind == 2) {
    const auto* qt = static_cast<const QuadtreeControlSpace*>(cs);
    state.counters["bytes_per_node"] = static_cast<double>(qt->memoryBytes()) / qt->nodeCount();
  }
  if (kind == 3)
    state.counters["bytes_per_node"] = static_cast<double>(s.background->memoryBytes()) / s.background->nodeCount();
  if (cached) state.counters["hit_rate"] = static_cast<double>(cached->hits()) / (cached->hits() + cached->misses());
}
BENCHMARK(BM_ControlSpaceQuery)->ArgNames({"kind", "cache", "path"})->ArgsProduct({{0, 1, 2, 3}, {0, 1}, {0, 1}});

std::vector<MetricSource> radialSources(int n) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0), h(0.002, 0.02), a(-1.5, 1.5), ar(1.0, 5.0);
  std::vector<MetricSource> out(n);
  for (auto& s : out) {
    const double x = u(rng);
    const double y = u(rng);
    const double h1 = h(rng);
    const double alpha = a(rng);
    const double stretch = ar(rng);
    s = RadialSource{Vec2(x, y), Metric::fromSizes(alpha, h1, h1 * stretch), 0.0};
  }
  return out;
}

std::unique_ptr<AdaptiveControlSpace> emptySpace(bool quadtree) {
  if (quadtree) {
    QuadtreeOptions q;
    q.maxLevel = 12;
    return std::make_unique<QuadtreeControlSpace>(csUnitBox(), q);
  }
  BackgroundMeshOptions b;
  b.maxLevel = 14;
  return std::make_unique<BackgroundMeshControlSpace>(csUnitBox(), b);
}

// Args: number of sources, quadtree (1) or background mesh (0), smoothing dr=2 (0 off,
// 1 on, 2 on but only between free nodes: GradationOptions::throughHangingNodes = false).
void BM_ControlSpaceBuildFromRadialSources(benchmark::State& state) {
  const std::vector<MetricSource> sources = radialSources(static_cast<int>(state.range(0)));
  int nodes = 0;
  for (auto _ : state) {
    auto cs = emptySpace(state.range(1) != 0);
    insertSources(*cs, sources);
    if (state.range(2)) {
      GradationOptions g;
      g.ratio = 2.0;
      g.throughHangingNodes = state.range(2) == 1;
      smoothGradation(*cs, g);
    }
    nodes = cs->nodeCount();
    benchmark::DoNotOptimize(cs);
  }
  state.counters["nodes"] = nodes;
  state.SetLabel(state.range(1) ? "quadtree" : "background-mesh");
}
BENCHMARK(BM_ControlSpaceBuildFromRadialSources)
    ->ArgNames({"sources", "quadtree", "smooth"})
    ->ArgsProduct({{1000, 10000, 100000}, {1, 0}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

// Smoothing alone against node count (sharp field: a boundary layer with slope 1 and a spot).
void BM_ControlSpaceSmoothing(benchmark::State& state) {
  const bool quadtree = state.range(1) != 0;
  auto base = emptySpace(quadtree);
  // Uniform refinement to the requested level, then a sharp field.
  const int level = static_cast<int>(state.range(0));
  const double size = 1.5 / (1 << level);
  base->refine([&](const ControlElement& e) { return e.size > size; }, nullptr);
  for (int i = 0; i < base->nodeCount(); ++i) {
    const Vec2 p = base->nodePosition(i);
    const Metric layer = Metric::fromSizes(0.0, 0.2, std::min(0.001 + std::abs(p.y() - 0.5), 0.2));
    base->setNodeMetric(
        i, intersect(layer, Metric::isotropic(std::min(0.002 + 3.0 * (p - Vec2(0.25, 0.25)).norm(), 0.2))));
  }
  base->applyConstraints();
  for (auto _ : state) {
    state.PauseTiming();
    auto cs = base->clone();
    state.ResumeTiming();
    GradationOptions g;
    g.ratio = 2.0;
    benchmark::DoNotOptimize(smoothGradation(*cs, g));
  }
  state.counters["nodes"] = base->nodeCount();
  state.SetLabel(quadtree ? "quadtree" : "background-mesh");
}
BENCHMARK(BM_ControlSpaceSmoothing)
    ->ArgNames({"level", "quadtree"})
    ->ArgsProduct({{6, 7, 8, 9}, {1, 0}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

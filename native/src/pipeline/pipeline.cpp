// The end-to-end runs; the only file of the pipeline that calls the planar mesher.
#include "anisomesh/pipeline/pipeline.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "anisomesh/boundary/boundary_updates.h"
#include "anisomesh/boundary/discretize.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/control_space_spec.h"
#include "anisomesh/controlspace/query_cache.h"
#include "anisomesh/core/clock.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/number_text.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/pipeline/algorithm1.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/element_estimate.h"
#include "anisomesh/pipeline/mesh_metric_field.h"
#include "anisomesh/pipeline/remesh_geometry.h"

namespace anisomesh {
namespace {

// Runs f on cs, through a section 4 query cache when tolerance > 0 (a fresh one per call:
// cs may have changed since), adding the cache's counts to the report.
template <class F>
auto throughCache(const ControlSpace& cs, double tolerance, PipelineReport& r, F&& f) {
  if (!(tolerance > 0.0)) return f(cs);
  QueryCacheOptions o;
  o.tolerance = tolerance;
  const CachedControlSpace cache(cs, o);
  auto result = f(static_cast<const ControlSpace&>(cache));
  r.cacheHits += cache.hits();
  r.cacheMisses += cache.misses();
  return result;
}

void countBoundary(const std::vector<BoundaryLoop>& loops, PipelineReport* report) {
  if (!report) return;
  report->boundaryLoops = int(loops.size());
  report->boundaryPoints = 0;
  for (const auto& l : loops) report->boundaryPoints += int(l.points.size());
}

// MMG's -hausd: curvature sources where a chord of the discretization is farther than
// options.hausdorff from its curve, then the domain discretized again, until no chord is
// (or 8 rounds: a note says so, e.g. when hmin forbids the sizes needed).
void hausdorffRounds(const Domain& domain, const RemeshOptions& options, const DiscretizeOptions& d,
                     AdaptiveControlSpace& cs, std::vector<BoundaryLoop>& loops, PipelineReport& r) {
  BoundaryUpdateOptions u;
  u.chordTolerance = std::numeric_limits<double>::infinity();
  u.chordDistance = options.hausdorff;
  for (int round = 0;; ++round) {
    std::vector<MetricSource> sources;
    chordSources(domain, cs, u, &sources);
    if (sources.empty()) break;
    if (round >= u.maxRounds) {
      r.updatesConverged = false;
      r.notes.push_back("-hausd: chords farther than " + numberText(options.hausdorff) + " from the boundary after " +
                        std::to_string(u.maxRounds) + " rounds");
      break;
    }
    r.chordSources += int(sources.size());
    r.updateRounds = round + 1;
    DiscreteInsertionOptions o;
    o.source.sizeFactor = 0.25;              // as the case sources (case_control_space.cpp)
    AdaptiveControlSpace::NodeState before;  // the smooth space, when it is smoothed again below
    if (options.hgrad > 0) before = cs.nodeState();
    insertSources(cs, sources, o);
    if (options.hmin > 0 || options.hmax > 0)
      clampSizes(cs, options.hmin > 0 ? options.hmin : std::numeric_limits<double>::min(),
                 options.hmax > 0 ? options.hmax : std::numeric_limits<double>::infinity());
    if (options.hgrad > 0) {  // smooth before this round: only the chords' region again
      GradationOptions g;
      g.ratio = options.hgrad;
      resmoothGradation(cs, cs.nodesChangedSince(before), g);
    }
    loops =
        throughCache(cs, options.queryCache, r, [&](const ControlSpace& q) { return discretizeDomain(domain, q, d); });
  }
  r.controlElements = cs.elementCount();
  r.controlNodes = cs.nodeCount();
}

}  // namespace

PlanarMesherOptions mesherOptionsFromCase(const CaseSpec& spec) {
  PlanarMesherOptions o;
  o.quads = spec.options.quads || spec.options.allQuads;
  o.allQuads = spec.options.allQuads;
  o.maxElements = spec.options.maxElements;
  return o;
}

namespace {

// A planar case as Algorithm 1 sees it: one patch on the plane.
class PlanarCaseSteps final : public Algorithm1Steps {
 public:
  PlanarCaseSteps(const CaseSpec& spec, const BoundaryUpdateOptions& updates, PipelineReport& r,
                  const std::function<bool(double)>& progress)
      : spec_(spec), updates_(updates), r_(r), progress_(progress) {}

  void buildControlSpaces() override {
    const auto t = Clock::now();
    cs_ = withStage("control-space construction", [&] { return buildCaseControlSpace(spec_, progress_); });
    r_.secondsControlSpace = secondsSince(t);
    analytic_ = caseAnalyticMetric(spec_);
    mesher_ = mesherOptionsFromCase(spec_);
    mesher_.progress = progress_;
    // The boundary checks' triangulation, for the meshing on the same loops.
    mesher_.boundaryCache = makeBoundaryTriangulationCache();
    withStage("element estimate", [&] {
      checkElementEstimate(spec_.domain, *cs_, mesher_.maxElements, "element estimate before contour discretization");
    });
    d_.maxSegments = std::max<std::int64_t>(1, mesher_.maxElements);
  }

  // The first round discretizes every contour; later rounds only the contours marked
  // invalid (a segment outside [lengthMin, lengthMax] or a chord too far from the curve,
  // measured in the control space of that round), the others keep their points.
  void discretizeInvalidContours(int round) override {
    const auto t = Clock::now();
    if (round == 0 || std::find(invalid_.begin(), invalid_.end(), 1) != invalid_.end()) {
      const std::vector<BoundaryLoop> next = throughCache(
          *cs_, cacheTolerance(), r_, [&](const ControlSpace& q) { return discretizeDomain(spec_.domain, q, d_); });
      if (round == 0) {
        loops_ = next;
        fresh_.assign(loops_.size(), 1);
      } else {
        fresh_ = keepValidContours(loops_, next, invalid_);
        for (char f : fresh_) r_.rediscretizedContours += f;
      }
    } else {
      fresh_.assign(loops_.size(), 0);
    }
    r_.secondsDiscretization += secondsSince(t);
  }

  bool checkBoundaries(int round) override {
    const auto t = Clock::now();
    // (a) segment lengths: short ones update the control space, those outside
    // [lengthMin, lengthMax] make their contour invalid.
    SegmentLengthCheck lengths = checkSegmentLengths(loops_, *cs_, updates_);
    invalid_ = lengths.invalidContours;
    r_.shortSegments += int(lengths.shortSegments.size());
    r_.invalidSegments += lengths.invalidSegments;
    // (b) chord deviation, (c) proximity in the boundary triangulation.
    std::vector<MetricSource> sources;
    r_.maxChordDeviation = chordSources(spec_.domain, *cs_, updates_, &sources, &invalid_);
    const int chords = int(sources.size());
    PlanarMesherOptions b = mesher_;
    b.boundaryOnly = true;
    b.quads = b.allQuads = false;
    b.timings = nullptr;
    // The update rounds report no progress of their own but can still be cancelled.
    if (progress_) b.progress = [this](double) { return progress_(0.0); };
    const Mesh boundaryMesh = throughCache(*cs_, cacheTolerance(), r_,
                                           [&](const ControlSpace& q) { return meshPlanarBoundary(loops_, q, b); });
    const int gaps = proximitySources(loops_, boundaryMesh, *cs_, updates_, &sources);
    const int shortSources = shortSegmentSources(lengths.shortSegments, *cs_, spec_.controlSpace.hmin, &sources);
    r_.chordSources += chords;
    r_.proximitySources += gaps;
    r_.shortSegmentSources += shortSources;
    const int refined = refineNearSegments(*cs_, lengths.shortSegments, analytic_);
    r_.refinedElements += refined;
    const bool changed = !sources.empty() || refined > 0;
    if (changed) {
      addCaseSources(*cs_, spec_, sources);
      // The sources of a round can ask for far more elements than the case (a hole 1e-6
      // from the outer contour): refused now, not after more rounds of ever finer contours.
      const std::string stage = "element estimate after boundary update round " + std::to_string(round + 1);
      checkElementEstimate(spec_.domain, *cs_, mesher_.maxElements, stage.c_str());
    }
    r_.secondsUpdates += secondsSince(t);
    return changed;
  }

  bool hasStaleInvalidContour() const override {
    for (size_t k = 0; k < invalid_.size(); ++k)
      if (invalid_[k] && !fresh_[k]) return true;
    return false;
  }

  Mesh meshPatches() override {
    countBoundary(loops_, &r_);
    r_.controlElements = cs_->elementCount();
    r_.controlNodes = cs_->nodeCount();
    const auto t = Clock::now();
    PlanarMesherOptions finalOptions = mesher_;
    finalOptions.timings = &r_.mesherTimings;
    Mesh mesh = throughCache(*cs_, cacheTolerance(), r_,
                             [&](const ControlSpace& q) { return meshPlanarBoundary(loops_, q, finalOptions); });
    r_.secondsMeshing = secondsSince(t);
    return mesh;
  }

  std::unique_ptr<AdaptiveControlSpace> releaseControlSpace() { return std::move(cs_); }

 private:
  double cacheTolerance() const { return spec_.controlSpace.queryCache; }

  const CaseSpec& spec_;
  const BoundaryUpdateOptions& updates_;
  PipelineReport& r_;
  const std::function<bool(double)>& progress_;
  std::unique_ptr<AdaptiveControlSpace> cs_;
  MetricFunction analytic_;
  PlanarMesherOptions mesher_;
  DiscretizeOptions d_;
  std::vector<BoundaryLoop> loops_;
  std::vector<char> invalid_, fresh_;
};

}  // namespace

Mesh meshCase(const CaseSpec& spec, PipelineReport* report, const BoundaryUpdateOptions& updates,
              std::unique_ptr<AdaptiveControlSpace>* controlSpace, const std::function<bool(double)>& progress) {
  PipelineReport local;
  PipelineReport& r = report ? *report : local;
  const auto t = Clock::now();
  validateDomain(spec.domain);
  r.secondsGeometry = secondsSince(t);
  PlanarCaseSteps steps(spec, updates, r, progress);
  Algorithm1Report a;
  Mesh mesh = runAlgorithm1(steps, updates, &a);
  r.updateRounds = a.rounds;
  r.updatesConverged = a.converged;
  if (!a.note.empty()) r.notes.push_back(a.note);
  if (controlSpace) *controlSpace = steps.releaseControlSpace();
  return mesh;
}

std::unique_ptr<AdaptiveControlSpace> buildRemeshControlSpace(const Mesh& input, const std::vector<Metric>& metrics,
                                                              const RemeshOptions& options) {
  require(int(metrics.size()) == input.vertexCount(), ErrorCode::InvalidArgument,
          "remesh: " + std::to_string(metrics.size()) + " metrics for " + std::to_string(input.vertexCount()) +
              " vertices");
  require(input.vertexCount() > 0, ErrorCode::InvalidArgument, "remesh: the input mesh has no vertices");
  ControlSpaceSpec s;
  s.kind = ControlSpaceKind::BackgroundMesh;
  s.backgroundInterpolation = BackgroundInterpolation::Linear;
  Box2 box;
  box.lo = box.hi = input.points[0].head<2>();
  for (const Vec3& p : input.points) {
    box.lo = box.lo.cwiseMin(p.head<2>());
    box.hi = box.hi.cwiseMax(p.head<2>());
  }
  const Vec2 margin = Vec2::Constant(0.01 * std::max(box.size().norm(), 1e-12));
  box.lo -= margin;
  box.hi += margin;
  s.box = box;
  if (options.insertion == RemeshMetricInsertion::PiecewiseLinear) {
    // Continuous source (section 2.3): exact values at the control nodes, elements split
    // where the field varies; the input triangles only serve to evaluate it.
    auto field = std::make_shared<const TriangleMeshMetricField>(input, metrics);
    s.analytic = [field](const Vec2& p) { return field->metricAt(p); };
    s.refineThreshold = options.refineThreshold;
    s.refineMinMetricSize = options.refineMinMetricSize;
    s.analyticConcurrent = true;  // TriangleMeshMetricField queries are const and pure
    s.analyticDomain = [field](const Box2& b) { return field->meets(b); };
  } else {
    NodeSource nodes;
    for (const Vec3& p : input.points) nodes.points.push_back(p.head<2>());
    nodes.metrics = metrics;
    s.sources.emplace_back(std::in_place_type<NodeSource>, std::move(nodes));
  }
  s.hmin = options.hmin;
  s.hmax = options.hmax;
  s.gradation = options.hgrad;
  s.limits.maxNodes =
      options.maxControlNodes > 0 ? options.maxControlNodes : controlSpaceNodeBudget(options.mesher.maxElements);
  s.limits.progress = options.mesher.progress;
  return buildAdaptiveControlSpace(s);
}

namespace {

// remesh; releaseInput (when set) is called once the input and its metrics are no longer
// read (after the boundary loops and the control space are built).
Mesh remeshImpl(const Mesh& input, const std::vector<Metric>& metrics, const RemeshOptions& options,
                PipelineReport* report, std::unique_ptr<AdaptiveControlSpace>* controlSpace,
                const std::function<void()>& releaseInput) {
  PipelineReport local;
  PipelineReport& r = report ? *report : local;
  auto stage = [&](const char* name) {
    if (options.onStage) options.onStage(name);
  };
  stage("boundary");
  // A non-finite vertex is named here (the boundary loops would refuse it as a polyline
  // point without saying which): 1-based, as Medit numbers vertices.
  for (size_t v = 0; v < input.points.size(); ++v)
    require(input.points[v].allFinite(), ErrorCode::InvalidArgument,
            "remesh: vertex " + std::to_string(v + 1) + " of the input mesh has a coordinate that is not finite");
  auto t = Clock::now();
  LoopDomainOptions loopOptions;
  loopOptions.smooth = options.hausdorff > 0;
  if (options.ridgeAngle >= 0)
    loopOptions.cornerAngle = options.ridgeAngle;
  else if (loopOptions.smooth)
    loopOptions.cornerAngle = 0.7853981633974483;  // pi / 4
  const Domain domain = domainFromBoundaryLoops(boundaryLoopsFromMesh(input), loopOptions);
  validateDomain(domain);
  r.secondsGeometry = secondsSince(t);
  stage("control space");
  t = Clock::now();
  std::unique_ptr<AdaptiveControlSpace> cs =
      withStage("control-space construction", [&] { return buildRemeshControlSpace(input, metrics, options); });
  r.secondsControlSpace = secondsSince(t);
  if (releaseInput) releaseInput();
  r.controlElements = cs->elementCount();
  r.controlNodes = cs->nodeCount();
  withStage("element estimate", [&] {
    checkElementEstimate(domain, *cs, options.mesher.maxElements, "element estimate before contour discretization");
  });
  stage("discretization");
  t = Clock::now();
  DiscretizeOptions d;
  d.maxSegments = std::max<std::int64_t>(1, options.mesher.maxElements);
  std::vector<BoundaryLoop> loops =
      throughCache(*cs, options.queryCache, r, [&](const ControlSpace& q) { return discretizeDomain(domain, q, d); });
  if (options.hausdorff > 0) hausdorffRounds(domain, options, d, *cs, loops, r);
  r.secondsDiscretization = secondsSince(t);
  countBoundary(loops, report);
  stage("meshing");
  t = Clock::now();
  PlanarMesherOptions finalOptions = options.mesher;
  finalOptions.timings = &r.mesherTimings;
  Mesh mesh = throughCache(*cs, options.queryCache, r,
                           [&](const ControlSpace& q) { return meshPlanarBoundary(loops, q, finalOptions); });
  r.secondsMeshing = secondsSince(t);
  if (controlSpace) *controlSpace = std::move(cs);
  return mesh;
}

}  // namespace

Mesh remesh(const Mesh& input, const std::vector<Metric>& metrics, const RemeshOptions& options, PipelineReport* report,
            std::unique_ptr<AdaptiveControlSpace>* controlSpace) {
  return remeshImpl(input, metrics, options, report, controlSpace, nullptr);
}

Mesh remesh(Mesh&& input, std::vector<Metric>&& metrics, const RemeshOptions& options, PipelineReport* report,
            std::unique_ptr<AdaptiveControlSpace>* controlSpace) {
  Mesh carrier = std::move(input);
  std::vector<Metric> carrierMetrics = std::move(metrics);
  return remeshImpl(carrier, carrierMetrics, options, report, controlSpace, [&] {
    carrier = Mesh();
    std::vector<Metric>().swap(carrierMetrics);
  });
}

Mesh meshSurfaceCase(const SurfaceCaseSpec& spec, SurfaceMeshReport* report) {
  return meshSurfaceModel(spec.model, spec.options, report);
}

}  // namespace anisomesh

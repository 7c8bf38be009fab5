// The end-to-end runs; the only file of the pipeline that calls the planar mesher.
#include "anisomesh/pipeline/pipeline.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/control_space_spec.h"
#include "anisomesh/controlspace/query_cache.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/number_text.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/boundary/discretize.h"
#include "anisomesh/boundary/boundary_updates.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/element_estimate.h"
#include "anisomesh/pipeline/mesh_metric_field.h"
#include "anisomesh/pipeline/remesh_geometry.h"

namespace anisomesh {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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
    o.source.sizeFactor = 0.25;  // as the case sources (case_control_space.cpp)
    insertSources(cs, sources, o);
    if (options.hmin > 0 || options.hmax > 0)
      clampSizes(cs, options.hmin > 0 ? options.hmin : std::numeric_limits<double>::min(),
                 options.hmax > 0 ? options.hmax : std::numeric_limits<double>::infinity());
    if (options.hgrad > 0) {
      GradationOptions g;
      g.ratio = options.hgrad;
      smoothGradation(cs, g);
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

Mesh meshCase(const CaseSpec& spec, PipelineReport* report, const BoundaryUpdateOptions& updates,
              std::unique_ptr<AdaptiveControlSpace>* controlSpace, const std::function<bool(double)>& progress) {
  PipelineReport local;
  PipelineReport& r = report ? *report : local;
  auto t = Clock::now();
  validateDomain(spec.domain);
  r.secondsGeometry = secondsSince(t);

  t = Clock::now();
  std::unique_ptr<AdaptiveControlSpace> cs =
      withStage("control-space construction", [&] { return buildCaseControlSpace(spec, progress); });
  r.secondsControlSpace = secondsSince(t);
  const MetricFunction analytic = caseAnalyticMetric(spec);
  PlanarMesherOptions mesher = mesherOptionsFromCase(spec);
  mesher.progress = progress;
  withStage("element estimate", [&] {
    checkElementEstimate(spec.domain, *cs, mesher.maxElements, "element estimate before contour discretization");
  });
  DiscretizeOptions d;
  d.maxSegments = std::max<std::int64_t>(1, mesher.maxElements);
  const double cacheTolerance = spec.controlSpace.queryCache;

  // Section 3.2 loop: the first round discretizes every contour; later rounds only the
  // contours marked invalid (a segment outside [lengthMin, lengthMax] or a chord too far
  // from the curve, measured in the control space of that round), the others keep their
  // points. It ends when no contour is invalid and the control space did not change.
  std::vector<BoundaryLoop> loops;
  std::vector<char> invalid, fresh;
  r.updateRounds = 0;
  r.updatesConverged = true;
  for (int round = 0;; ++round) {
    t = Clock::now();
    if (round == 0 || std::find(invalid.begin(), invalid.end(), 1) != invalid.end()) {
      const std::vector<BoundaryLoop> next = throughCache(
          *cs, cacheTolerance, r, [&](const ControlSpace& q) { return discretizeDomain(spec.domain, q, d); });
      if (round == 0) {
        loops = next;
        fresh.assign(loops.size(), 1);
      } else {
        fresh = keepValidContours(loops, next, invalid);
        for (char f : fresh) r.rediscretizedContours += f;
      }
    } else {
      fresh.assign(loops.size(), 0);
    }
    r.secondsDiscretization += secondsSince(t);
    r.updateRounds = round + 1;
    if (!updates.enabled) break;
    if (round >= updates.maxRounds) {
      r.updatesConverged = false;
      r.notes.push_back("section 3.2 updates stopped after " + std::to_string(updates.maxRounds) + " rounds");
      break;
    }
    t = Clock::now();
    // (a) segment lengths: short ones update the control space, those outside
    // [lengthMin, lengthMax] make their contour invalid.
    SegmentLengthCheck lengths = checkSegmentLengths(loops, *cs, updates);
    invalid = lengths.invalidContours;
    r.shortSegments += int(lengths.shortSegments.size());
    r.invalidSegments += lengths.invalidSegments;
    // (b) chord deviation, (c) proximity in the boundary triangulation.
    std::vector<MetricSource> sources;
    r.maxChordDeviation = chordSources(spec.domain, *cs, updates, &sources, &invalid);
    const int chords = int(sources.size());
    PlanarMesherOptions b = mesher;
    b.boundaryOnly = true;
    b.quads = b.allQuads = false;
    b.timings = nullptr;
    // The update rounds report no progress of their own but can still be cancelled.
    if (progress) b.progress = [&progress](double) { return progress(0.0); };
    const Mesh boundaryMesh =
        throughCache(*cs, cacheTolerance, r, [&](const ControlSpace& q) { return meshPlanarBoundary(loops, q, b); });
    const int gaps = proximitySources(loops, boundaryMesh, *cs, updates, &sources);
    const int shortSources = shortSegmentSources(lengths.shortSegments, *cs, spec.controlSpace.hmin, &sources);
    r.chordSources += chords;
    r.proximitySources += gaps;
    r.shortSegmentSources += shortSources;
    const int refined = refineNearSegments(*cs, lengths.shortSegments, analytic);
    r.refinedElements += refined;
    const bool changed = !sources.empty() || refined > 0;
    if (changed) addCaseSources(*cs, spec, sources);
    r.secondsUpdates += secondsSince(t);
    // An invalid contour discretized in this very control space would come out the same
    // (e.g. curves shorter than half a size): only a change makes another round useful.
    bool redo = changed;
    for (size_t k = 0; k < invalid.size() && !redo; ++k) redo = invalid[k] && !fresh[k];
    if (!redo) break;
  }
  countBoundary(loops, report);
  r.controlElements = cs->elementCount();
  r.controlNodes = cs->nodeCount();

  t = Clock::now();
  PlanarMesherOptions finalOptions = mesher;
  finalOptions.timings = &r.mesherTimings;
  Mesh mesh = throughCache(*cs, cacheTolerance, r,
                           [&](const ControlSpace& q) { return meshPlanarBoundary(loops, q, finalOptions); });
  r.secondsMeshing = secondsSince(t);
  if (controlSpace) *controlSpace = std::move(cs);
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

Mesh remesh(const Mesh& input, const std::vector<Metric>& metrics, const RemeshOptions& options, PipelineReport* report,
            std::unique_ptr<AdaptiveControlSpace>* controlSpace) {
  PipelineReport local;
  PipelineReport& r = report ? *report : local;
  auto stage = [&](const char* name) {
    if (options.onStage) options.onStage(name);
  };
  stage("boundary");
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

Mesh meshSurfaceCase(const SurfaceCaseSpec& spec, SurfaceMeshReport* report) {
  return meshSurfaceModel(spec.model, spec.options, report);
}

}  // namespace anisomesh

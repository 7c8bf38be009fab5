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
#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/geometry/discretize.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/element_estimate.h"
#include "anisomesh/pipeline/mesh_metric_field.h"
#include "anisomesh/pipeline/remesh_geometry.h"

namespace anisomesh {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// Metric length of the straight segment pq (Simpson's rule on |Mt(x) (q - p)|).
double segmentMetricLength(const ControlSpace& cs, const Vec2& p, const Vec2& q) {
  const Vec2 d = q - p;
  return (cs.metricAt(p).length(d) + 4.0 * cs.metricAt(0.5 * (p + q)).length(d) + cs.metricAt(q).length(d)) / 6.0;
}

bool isCurved(const Curve& c) {
  const std::string t = c.typeName();
  return t != "line" && t != "polyline";
}

// Largest distance of c([a, b]) from its chord, by sampling.
double chordDeviation(const Curve& c, double a, double b) {
  const Vec2 p = c.point(a), q = c.point(b);
  double dev = 0.0;
  constexpr int kSamples = 8;
  for (int k = 1; k < kSamples; ++k)
    dev = std::max(dev, pointSegmentDistance(c.point(a + (b - a) * k / kSamples), p, q));
  return dev;
}

double curvatureRadius(const Curve& c, double t) {
  const Vec2 d1 = c.derivative(t), d2 = c.secondDerivative(t);
  const double cross = std::abs(d1.x() * d2.y() - d1.y() * d2.x());
  const double n = d1.norm();
  return cross > 0 ? n * n * n / cross : std::numeric_limits<double>::infinity();
}

// Section 3.2 (b): curvature sources along the chords of curved contours deviating
// from the curve by more than tolerance * chord. Returns the largest relative deviation.
double chordSources(const Domain& domain, const ControlSpace& cs, const BoundaryUpdateOptions& o,
                    std::vector<MetricSource>* out) {
  double worst = 0.0;
  std::vector<const Contour*> contours{&domain.outer};
  for (const Contour& h : domain.holes) contours.push_back(&h);
  for (const Contour* contour : contours)
    for (const CurveUse& use : contour->curves) {
      const Curve& c = *use.curve;
      if (!isCurved(c)) continue;
      const std::vector<double> ts = discretizeCurve(c, cs, contour->curves.size() == 1 ? 3 : 1);
      for (size_t i = 0; i + 1 < ts.size(); ++i) {
        const double chord = (c.point(ts[i + 1]) - c.point(ts[i])).norm();
        if (chord <= 0) continue;
        const double rel = chordDeviation(c, ts[i], ts[i + 1]) / chord;
        worst = std::max(worst, rel);
        if (rel <= o.chordTolerance) continue;
        // Tangent size from the sagitta s = h^2 / (8 R): s / h <= tol for h <= 8 R tol;
        // 0.75 leaves room for the rounding of the discretization.
        const int pieces = 8;
        for (int k = 0; k < pieces; ++k) {
          const double a = ts[i] + (ts[i + 1] - ts[i]) * k / pieces, b = ts[i] + (ts[i + 1] - ts[i]) * (k + 1) / pieces;
          const double r = std::min({curvatureRadius(c, a), curvatureRadius(c, 0.5 * (a + b)), curvatureRadius(c, b)});
          if (!std::isfinite(r)) continue;
          const double h1 = 0.75 * 8.0 * r * o.chordTolerance;
          const Vec2 t = c.derivative(0.5 * (a + b));
          const Vec2 pa = c.point(a), pb = c.point(b);
          if ((pb - pa).norm() <= 1e-12 * std::max(1.0, pa.norm())) continue;
          out->emplace_back(std::in_place_type<SegmentSource>,
                            SegmentSource{pa, pb, Metric::fromSizes(pm::atan2(t.y(), t.x()), h1, o.dMax * h1),
                                          chordDeviation(c, a, b)});  // emplace: see case_control_space.cpp
        }
      }
    }
  return worst;
}

// Where each boundary point sits: loop, index in the loop, arc length along the loop.
struct BoundaryIndex {
  std::vector<int> loop, index;
  std::vector<double> arc;
  std::vector<double> loopLength;
  std::vector<int> loopSize;
};

BoundaryIndex indexBoundary(const std::vector<BoundaryLoop>& loops) {
  BoundaryIndex b;
  for (size_t l = 0; l < loops.size(); ++l) {
    const auto& pts = loops[l].points;
    double s = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) {
      b.loop.push_back(int(l));
      b.index.push_back(int(i));
      b.arc.push_back(s);
      s += (pts[(i + 1) % pts.size()] - pts[i]).norm();
    }
    b.loopLength.push_back(s);
    b.loopSize.push_back(int(pts.size()));
  }
  return b;
}

// Two boundary points belong to non-adjacent boundary segments when they are on different
// loops, or farther apart along the loop than twice their distance (a gap or a narrow
// part, not a gently curved contour) and not neighbours.
bool nonAdjacent(const BoundaryIndex& b, const std::vector<Vec2>& pts, int i, int j) {
  if (b.loop[i] != b.loop[j]) return true;
  const int n = b.loopSize[b.loop[i]];
  const int di = std::abs(b.index[i] - b.index[j]);
  if (std::min(di, n - di) < 2) return false;
  const double da = std::abs(b.arc[i] - b.arc[j]);
  const double along = std::min(da, b.loopLength[b.loop[i]] - da);
  return along > 2.0 * (pts[i] - pts[j]).norm();
}

// Section 3.2 (c): sources across thin boundary triangles.
int proximitySources(const std::vector<BoundaryLoop>& loops, const Mesh& boundaryMesh, const ControlSpace& cs,
                     const BoundaryUpdateOptions& o, std::vector<MetricSource>* out) {
  const BoundaryIndex b = indexBoundary(loops);
  std::vector<Vec2> pts;
  for (const Vec3& p : boundaryMesh.points) pts.push_back(p.head<2>());
  const int nb = int(b.loop.size());
  std::vector<Mat2> mt(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) mt[i] = cs.metricAt(pts[i]).transform();
  const double unitArea = std::sqrt(3.0) / 4.0;
  int added = 0;
  for (const auto& t : boundaryMesh.triangles) {
    if (t[0] >= nb || t[1] >= nb || t[2] >= nb) continue;
    if (!nonAdjacent(b, pts, t[0], t[1]) && !nonAdjacent(b, pts, t[1], t[2]) && !nonAdjacent(b, pts, t[2], t[0]))
      continue;
    const Vec2 &p0 = pts[t[0]], &p1 = pts[t[1]], &p2 = pts[t[2]];
    const Vec2 e1 = p1 - p0, e2 = p2 - p0;
    const double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    const Mat2 m = (mt[t[0]] + mt[t[1]] + mt[t[2]]) / 3.0;
    if (area * std::abs(m.determinant()) >= o.eps2 * unitArea) continue;
    const double longest = std::max({e1.norm(), e2.norm(), (p2 - p1).norm()});
    const double width = 2.0 * area / longest;  // the triangle's height across its longest edge
    if (!(width > 0)) continue;
    const Vec2 centroid = (p0 + p1 + p2) / 3.0;
    const double radius = std::max({(p0 - centroid).norm(), (p1 - centroid).norm(), (p2 - centroid).norm()});
    out->emplace_back(std::in_place_type<RadialSource>,
                      RadialSource{centroid, Metric::isotropic(width / o.gapElements), radius});
    ++added;
  }
  return added;
}

// Section 3.2 (a): refines the structure near short boundary segments so it resolves
// the metric there; new nodes take the analytic metric (when any) intersected with the
// interpolated one. Returns the number of elements added.
int refineNearSegments(AdaptiveControlSpace& cs, const std::vector<std::array<Vec2, 2>>& segments,
                       const MetricFunction& analytic) {
  if (segments.empty()) return 0;
  // A uniform grid of segment boxes keeps the predicate cheap.
  const Box2 box = cs.bounds();
  const int side = std::clamp(int(std::sqrt(double(segments.size()))) + 1, 1, 256);
  const Vec2 cell = box.size() / double(side);
  std::vector<std::vector<int>> grid(size_t(side) * side);
  auto cellOf = [&](double v, double lo, double h) { return std::clamp(int(std::floor((v - lo) / h)), 0, side - 1); };
  for (size_t k = 0; k < segments.size(); ++k) {
    const Vec2 lo = segments[k][0].cwiseMin(segments[k][1]), hi = segments[k][0].cwiseMax(segments[k][1]);
    for (int y = cellOf(lo.y(), box.lo.y(), cell.y()); y <= cellOf(hi.y(), box.lo.y(), cell.y()); ++y)
      for (int x = cellOf(lo.x(), box.lo.x(), cell.x()); x <= cellOf(hi.x(), box.lo.x(), cell.x()); ++x)
        grid[size_t(y) * side + x].push_back(int(k));
  }
  const int before = cs.elementCount();
  cs.refine(
      [&](const ControlElement& e) {
        for (int y = cellOf(e.box.lo.y(), box.lo.y(), cell.y()); y <= cellOf(e.box.hi.y(), box.lo.y(), cell.y()); ++y)
          for (int x = cellOf(e.box.lo.x(), box.lo.x(), cell.x()); x <= cellOf(e.box.hi.x(), box.lo.x(), cell.x()); ++x)
            for (int k : grid[size_t(y) * side + x]) {
              const Vec2 &a = segments[k][0], &b = segments[k][1];
              if (e.size <= (b - a).norm()) continue;
              if (segmentBoxDistance(a, b, e.box) <= 0.0) return true;
            }
        return false;
      },
      [&](int first, int last) {
        if (!analytic) return;
        for (int i = first; i < last; ++i)
          if (cs.nodeIsFree(i)) cs.setNodeMetric(i, intersect(cs.nodeMetric(i), analytic(cs.nodePosition(i))));
      });
  cs.applyConstraints();
  return cs.elementCount() - before;
}

void countBoundary(const std::vector<BoundaryLoop>& loops, PipelineReport* report) {
  if (!report) return;
  report->boundaryLoops = int(loops.size());
  report->boundaryPoints = 0;
  for (const auto& l : loops) report->boundaryPoints += int(l.points.size());
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

  std::vector<BoundaryLoop> loops;
  r.updateRounds = 0;
  r.updatesConverged = true;
  for (int round = 0;; ++round) {
    t = Clock::now();
    loops = withStage("contour discretization", [&] { return discretizeDomain(spec.domain, *cs, d); });
    r.secondsDiscretization += secondsSince(t);
    r.updateRounds = round + 1;
    if (!updates.enabled) break;
    if (round >= updates.maxRounds) {
      r.updatesConverged = false;
      r.notes.push_back("section 3.2 updates stopped after " + std::to_string(updates.maxRounds) + " rounds");
      break;
    }
    t = Clock::now();
    // (a) segment lengths.
    std::vector<std::array<Vec2, 2>> shortOnes;
    for (const BoundaryLoop& l : loops)
      for (size_t i = 0; i < l.points.size(); ++i) {
        const Vec2 &p = l.points[i], &q = l.points[(i + 1) % l.points.size()];
        const double len = segmentMetricLength(*cs, p, q);
        if (len < updates.eps1) shortOnes.push_back({p, q});
        if (len < updates.lengthMin || len > updates.lengthMax) ++r.invalidSegments;
      }
    r.shortSegments += int(shortOnes.size());
    // (b) chord deviation, (c) proximity in the boundary triangulation.
    std::vector<MetricSource> sources;
    r.maxChordDeviation = chordSources(spec.domain, *cs, updates, &sources);
    const int chords = int(sources.size());
    PlanarMesherOptions b = mesher;
    b.boundaryOnly = true;
    b.quads = b.allQuads = false;
    b.timings = nullptr;
    // The update rounds report no progress of their own but can still be cancelled.
    if (progress) b.progress = [&progress](double) { return progress(0.0); };
    int gaps = 0, refined = 0;
    withStage("section 3.2 control-space updates", [&] {
      const Mesh boundaryMesh = meshPlanarBoundary(loops, *cs, b);
      gaps = proximitySources(loops, boundaryMesh, *cs, updates, &sources);
      refined = refineNearSegments(*cs, shortOnes, analytic);
      if (!sources.empty() || refined > 0) addCaseSources(*cs, spec, sources);
    });
    r.chordSources += chords;
    r.proximitySources += gaps;
    r.refinedElements += refined;
    r.secondsUpdates += secondsSince(t);
    // Nothing changed: the discretization is final (contours whose lengths stay outside
    // [1/2, 2], e.g. curves shorter than half a size, cannot improve by re-discretizing).
    if (sources.empty() && refined == 0) break;
  }
  countBoundary(loops, report);
  r.controlElements = cs->elementCount();
  r.controlNodes = cs->nodeCount();

  t = Clock::now();
  PlanarMesherOptions finalOptions = mesher;
  finalOptions.timings = &r.mesherTimings;
  Mesh mesh = withStage("meshing", [&] { return meshPlanarBoundary(loops, *cs, finalOptions); });
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
  auto t = Clock::now();
  const Domain domain = domainFromBoundaryLoops(boundaryLoopsFromMesh(input));
  validateDomain(domain);
  r.secondsGeometry = secondsSince(t);
  t = Clock::now();
  std::unique_ptr<AdaptiveControlSpace> cs =
      withStage("control-space construction", [&] { return buildRemeshControlSpace(input, metrics, options); });
  r.secondsControlSpace = secondsSince(t);
  r.controlElements = cs->elementCount();
  r.controlNodes = cs->nodeCount();
  withStage("element estimate", [&] {
    checkElementEstimate(domain, *cs, options.mesher.maxElements, "element estimate before contour discretization");
  });
  t = Clock::now();
  DiscretizeOptions d;
  d.maxSegments = std::max<std::int64_t>(1, options.mesher.maxElements);
  const std::vector<BoundaryLoop> loops =
      withStage("contour discretization", [&] { return discretizeDomain(domain, *cs, d); });
  r.secondsDiscretization = secondsSince(t);
  countBoundary(loops, report);
  t = Clock::now();
  PlanarMesherOptions finalOptions = options.mesher;
  finalOptions.timings = &r.mesherTimings;
  Mesh mesh = withStage("meshing", [&] { return meshPlanarBoundary(loops, *cs, finalOptions); });
  r.secondsMeshing = secondsSince(t);
  if (controlSpace) *controlSpace = std::move(cs);
  return mesh;
}

}  // namespace anisomesh

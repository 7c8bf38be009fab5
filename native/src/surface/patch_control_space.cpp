// Surface meshing: the control space of each patch in its parameter plane (section 3.1:
// curvature of the surface and of the contours, user sources, gradation), its updates and glyphs.
#include "anisomesh/metric/metric_ellipse.h"
#include "model_mesher.h"

#include "anisomesh/pipeline/element_estimate.h"
#include "curvature_stage_cache.h"

namespace anisomesh {
namespace surface_mesher {

namespace {

// Section 3.1: the curvature of every contour curve in 3D, C(t) = S(c(t)), as sources along
// it before the first discretization (the section 3.2 chord check stays as a safeguard).
// At the middle of each of 64 pieces per curve: kappa = |C' x C''| / |C'|^3 with
// C' = J c', C'' = Suu cu'^2 + 2 Suv cu' cv' + Svv cv'^2 + J c''; size along the tangent T
// h = curvatureSize(kappa) (the surface sizing: chord tolerance / chordSafety^2, angle
// tolerance, clamps), across it (in the tangent plane) d_max h, along the normal h; the 3D
// metric is pulled back into (u, v) and applied within half the piece's (u, v) length of it.
// Pieces where h reaches hmax (nearly straight in 3D) add nothing.
std::vector<MetricSource> contourCurvatureSources(const SurfacePatch& patch, const SurfaceMetricOptions& sizing) {
  std::vector<MetricSource> out;
  const Surface& surf = *patch.surface;
  const int pieces = 64;
  for (int k = 0; k < contourCount(patch); ++k)
    for (const auto& cc : contourOf(patch, k).curves) {
      const Curve& c = *cc.curve;
      Vec2 prev = c.point(0.0);
      for (int i = 0; i < pieces; ++i) {
        const Vec2 nextPt = c.point(double(i + 1) / pieces);
        const Vec2 a = prev;
        prev = nextPt;
        if (!((nextPt - a).norm() > 0)) continue;
        const double t = (i + 0.5) / pieces;
        const Vec2 uv = c.point(t), d1 = c.derivative(t), d2 = c.secondDerivative(t);
        const SurfaceDerivatives d = surf.derivatives(uv);
        if (isDegenerate(d)) continue;
        const Vec3 c1 = d.su * d1.x() + d.sv * d1.y();
        const Vec3 c2 = d.suu * (d1.x() * d1.x()) + 2.0 * d.suv * (d1.x() * d1.y()) + d.svv * (d1.y() * d1.y()) +
                        d.su * d2.x() + d.sv * d2.y();
        const double speed = c1.norm();
        if (!(speed > 0)) continue;
        const double kappa = c1.cross(c2).norm() / (speed * speed * speed);
        const double h = curvatureSize(kappa, sizing);
        if (!(std::isfinite(h) && h < sizing.hmax)) continue;
        const Vec3 tan = c1 / speed;
        const Vec3 nrm = d.su.cross(d.sv).normalized();
        const Vec3 across = nrm.cross(tan).normalized();
        const double hx = std::min(sizing.hmax, sizing.maxAspectRatio * h);
        const Mat3 m3 =
            tan * tan.transpose() / (h * h) + across * across.transpose() / (hx * hx) + nrm * nrm.transpose() / (h * h);
        SegmentSource src;
        src.a = a;
        src.b = nextPt;
        src.metric = pullBackMetric(m3, d);
        src.radius = 0.5 * (nextPt - a).norm();
        out.emplace_back(src);
      }
    }
  return out;
}

// Section 3.1, curvature stage: the main-level grid from the surface's curvature (and the
// 3D sources), extrapolated where the surface is degenerate, then leaves split while the
// metric varies. counters.curvature() grows by the evaluations made.
std::unique_ptr<AdaptiveControlSpace> buildCurvatureStage(const SurfacePatch& patch,
                                                          const std::vector<Source3D>& sources3d,
                                                          const SurfaceMeshOptions& o,
                                                          const SurfaceMetricOptions& sizing, const QuadtreeOptions& qo,
                                                          const ControlSpaceLimits& limits, const Metric& fallback,
                                                          Counters& counters) {
  const Surface& surf = *patch.surface;
  SurfaceCurvatureControlSpace curv(patch.surface, sizing);
  if (!sources3d.empty()) {
    const double hmax = o.metric.hmax;
    curv.setUserMetric3D([sources3d, hmax](const Vec3& x) {
      double h = hmax;
      for (const Source3D& s : sources3d)
        if ((x - s.center).norm() <= s.radius) h = std::min(h, s.h);
      return Mat3(Mat3::Identity() / (h * h));
    });
  }
  // Timed one call in 32, as CountingControlSpace; from any thread (the surface keeps no
  // state, the tallies are per thread).
  auto eval = [&](const Vec2& p) {
    QueryTally& t = counters.mine();
    if ((t.curvature++ & 31) != 0) return curv.tryMetricAt(p);
    const auto t0 = Clock::now();
    std::optional<Metric> m = curv.tryMetricAt(p);
    t.curvatureSeconds += 32.0 * secondsSince(t0);
    return m;
  };
  auto cs = std::make_unique<QuadtreeControlSpace>(surf.domain(), qo);
  // The free nodes in [first, last) evaluated in parallel chunks, then set in node order
  // (the same field for any thread count); set(i, m) takes each.
  std::vector<std::optional<Metric>> sampled;
  auto sampleNodes = [&](int first, int last, const std::function<void(int, const std::optional<Metric>&)>& set) {
    sampled.assign(size_t(last - first), std::nullopt);
    parallelChunks(size_t(last - first), 256, [&](size_t, size_t b, size_t e) {
      for (size_t k = b; k < e; ++k)
        if (cs->nodeIsFree(first + int(k))) sampled[k] = eval(cs->nodePosition(first + int(k)));
    });
    for (int i = first; i < last; ++i)
      if (cs->nodeIsFree(i)) set(i, sampled[size_t(i - first)]);
  };

  cs->setLimits(limits);
  // Main-level grid: curvature where available, extrapolation elsewhere (section 3.1).
  sampleNodes(0, cs->nodeCount(), [&](int i, const std::optional<Metric>& m) {
    if (m)
      cs->setNodeMetric(i, *m);
    else
      cs->clearNodeInitialized(i);
  });
  extrapolateMetric(*cs, fallback);
  cs->applyConstraints();

  // Split leaves while corner metrics differ, or the analytic metric at the centre differs
  // from the bilinear value there (the average of the corners' Mt), but not below a
  // fraction of the requested size: finer leaves cannot change the mesh. The test only
  // reads (the structure and the surface): a batch's leaves are judged concurrently.
  const double thr = o.refineThreshold;
  cs->refineConcurrently(
      [&](const ControlElement& e) {
        Metric corners[4];
        double hsmall = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 4; ++k) {
          corners[k] = cs->nodeMetric(e.nodes[k]);
          hsmall = std::min(hsmall, corners[k].smallestSize());
        }
        if (e.size <= 0.5 * hsmall) return false;
        for (int a = 0; a < 4; ++a)
          for (int b = a + 1; b < 4; ++b)
            if (difference(corners[a], corners[b]) > thr) return true;
        const double w[4] = {0.25, 0.25, 0.25, 0.25};
        const auto m = eval(e.box.center());
        return m && difference(*m, weightedAverage(corners, w, 4)) > thr;
      },
      [&](int first, int last) {
        sampleNodes(first, last, [&](int i, const std::optional<Metric>& m) {
          if (m) cs->setNodeMetric(i, *m);
        });
      });
  cs->applyConstraints();
  return cs;
}

}  // namespace

std::unique_ptr<AdaptiveControlSpace> buildControlSpaceImpl(const SurfacePatch& patch,
                                                            const std::vector<Source3D>& sources3d,
                                                            const SurfaceMeshOptions& o, Counters& counters,
                                                            std::string* stageKeyOut) {
  const Surface& surf = *patch.surface;
  SurfaceMetricOptions sizing = o.metric;
  require(std::isfinite(o.chordSafety) && o.chordSafety > 0.0, ErrorCode::InvalidArgument, "chordSafety must be > 0");
  sizing.chordTolerance /= o.chordSafety * o.chordSafety;
  QuadtreeOptions qo;
  qo.initialLevel = o.initialLevel;
  qo.maxLevel = o.maxLevel;
  // The same bounds as planar cases: a node budget from the element budget, cancellable.
  ControlSpaceLimits limits;
  limits.maxNodes = o.maxControlNodes > 0 ? o.maxControlNodes : controlSpaceNodeBudget(o.mesher.maxElements);
  limits.progress = o.mesher.progress;
  const Metric fallback = Metric::isotropic(0.1 * surf.domain().size().norm());
  GradationOptions g;
  g.ratio = o.gradation;
  // The curvature stage (the surface's, then the contours' in 3D), smoothed, reads only the
  // surface, the sizing, the 3D sources, the contour sources and the gradation: a run with
  // the same ones (a 2D source dragged) starts from a copy of its result.
  const std::vector<MetricSource> contour =
      o.contourCurvature ? contourCurvatureSources(patch, sizing) : std::vector<MetricSource>{};
  std::string stageKey =
      curvatureStageKey(surf, sizing, sources3d, qo, o.refineThreshold, limits.maxNodes, o.gradation);
  if (!stageKey.empty()) appendSourceBits(stageKey, contour);
  CurvatureStage stage = findCurvatureStage(stageKey);
  std::unique_ptr<AdaptiveControlSpace> cs;
  DiscreteInsertionOptions io;
  io.fallbackMetric = fallback;
  if (stage.space) {
    cs = std::move(stage.space);
    cs->setLimits(limits);
    counters.mine().curvature += stage.evaluations;
  } else {
    const long long before = counters.curvature();
    cs = buildCurvatureStage(patch, sources3d, o, sizing, qo, limits, fallback, counters);
    if (!contour.empty()) insertSources(*cs, contour, io);
    if (o.gradation > 0.0) smoothGradation(*cs, g);
    stage.stage = storeCurvatureStage(stageKey, *cs, counters.curvature() - before);
  }
  if (stageKeyOut && stage.stage) *stageKeyOut = stageKey;
  if (!patch.sources.empty()) {
    AdaptiveControlSpace::NodeState smooth;  // the stage, when it is smoothed again below and not kept
    if (o.gradation > 0.0 && !stage.stage) smooth = cs->nodeState();
    insertSources(*cs, patch.sources, io);
    // The stage held the bound: the 2D sources' region is smoothed again, not the whole
    // structure (the stage's sizes limit the sources' ones as the sources' limit the stage's).
    if (o.gradation > 0.0)
      resmoothGradation(*cs, stage.stage ? cs->nodesChangedSince(*stage.stage) : cs->nodesChangedSince(smooth), g);
  }
  // Before any contour is discretized: the metric area of the patch (pulled back, so 3D
  // area over h^2) against the element budget.
  checkElementEstimate(patch.domain, *cs, o.mesher.maxElements, "element estimate before contour discretization");
  return cs;
}

PatchState::~PatchState() {
  counted.reset();  // (the views read cs: gone before it is given back)
  parameterized.reset();
  recycleCurvatureStage(stageKey, std::move(cs));
}

void ModelMesher::flushSources() {
  for (size_t p = 0; p < ps_.size(); ++p) {
    if (pending_[p].empty()) continue;
    AdaptiveControlSpace::NodeState before;  // the smooth space, when it is smoothed again below
    if (o_.gradation > 0.0) before = ps_[p].cs->nodeState();
    insertSources(*ps_[p].cs, pending_[p]);
    if (o_.gradation > 0.0) {  // smooth before the sources: only their region again
      GradationOptions g;
      g.ratio = o_.gradation;
      resmoothGradation(*ps_[p].cs, ps_[p].cs->nodesChangedSince(before), g);
    }
    pending_[p].clear();
    ps_[p].modified = true;
    refreshQueries(p);
  }
}

// Glyphs of the final control spaces: at control element (leaf) centres inside the patch,
// thinned so that accepted centres are at least 1.6 requested sizes apart (metric length
// >= 1.6 in the candidate's metric; larger elements first), so a picture stays readable.
std::vector<ControlSpaceGlyph> ModelMesher::glyphs() const {
  std::vector<ControlSpaceGlyph> out;
  for (size_t p = 0; p < m_.patches.size(); ++p) {
    const SurfacePatch& patch = m_.patches[p];
    const Box2 dom = patch.surface->domain();
    const auto outer = sampleContour(patch.domain.outer, 16);
    std::vector<std::vector<Vec2>> holes;
    for (const auto& h : patch.domain.holes) holes.push_back(sampleContour(h, 16));
    const AdaptiveControlSpace& cs = *ps_[p].cs;
    struct Cand {
      double size;
      Vec2 c;
      Metric m;
    };
    std::vector<Cand> cands;
    double smallest = std::numeric_limits<double>::infinity();
    for (const auto& nodes : cs.elementNodes()) {
      Vec2 c = Vec2::Zero(), lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (int n : nodes) {
        c += cs.nodePosition(n);
        lo = lo.cwiseMin(cs.nodePosition(n));
        hi = hi.cwiseMax(cs.nodePosition(n));
      }
      c /= double(nodes.size());
      bool inside = pointInPolygon(outer, c);
      for (const auto& h : holes) inside = inside && !pointInPolygon(h, c);
      if (!inside) continue;
      const Metric m = cs.metricAt(c);
      const MetricSizes ms = m.sizes();
      smallest = std::min({smallest, ms.h1, ms.h2});
      cands.push_back({(hi - lo).maxCoeff(), c, m});
    }
    std::stable_sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.size > b.size; });
    const double bin = std::max(0.5 * smallest, dom.size().maxCoeff() / 400.0);
    std::map<std::pair<long, long>, std::vector<Vec2>> accepted;
    auto binOf = [&](double x, double y) {
      return std::make_pair(long(std::floor((x - dom.lo.x()) / bin)), long(std::floor((y - dom.lo.y()) / bin)));
    };
    for (const Cand& cand : cands) {
      const double r = std::max(cand.m.sizes().h1, cand.m.sizes().h2);
      const auto b0 = binOf(cand.c.x() - r, cand.c.y() - r), b1 = binOf(cand.c.x() + r, cand.c.y() + r);
      bool free = true;
      for (long i = b0.first; i <= b1.first && free; ++i)
        for (long j = b0.second; j <= b1.second && free; ++j) {
          const auto it = accepted.find({i, j});
          if (it == accepted.end()) continue;
          for (const Vec2& q : it->second)
            if (cand.m.length(q - cand.c) < 1.6) free = false;
        }
      if (!free) continue;
      accepted[binOf(cand.c.x(), cand.c.y())].push_back(cand.c);
      ControlSpaceGlyph g;
      g.patch = int(p);
      for (const Vec2& uv : metricEllipse(cand.m, cand.c, 24, 0.5)) {
        g.uv.push_back(uv);
        g.xyz.push_back(patch.surface->point(uv.cwiseMax(dom.lo).cwiseMin(dom.hi)));
      }
      out.push_back(std::move(g));
    }
  }
  return out;
}

}  // namespace surface_mesher

std::unique_ptr<AdaptiveControlSpace> buildPatchControlSpace(const SurfacePatch& patch,
                                                             const std::vector<Source3D>& sources3d,
                                                             const SurfaceMeshOptions& options) {
  validate(options.metric);
  surface_mesher::Counters c;
  return surface_mesher::buildControlSpaceImpl(patch, sources3d, options, c);
}

}  // namespace anisomesh

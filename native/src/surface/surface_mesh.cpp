// Surface meshing, paper section 3 (Algorithm 1): per-patch control spaces in the
// parameter plane, shared contours discretized once in 3D, the invalidation loop
// (segment length, contour chord, boundary proximity), adaptation of neighbouring
// control spaces across shared contours, inner meshing and merging.
#include "anisomesh/surface/surface_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/geometry/discretize.h"

namespace anisomesh {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string fmt(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}
std::string fmtUv(const Vec2& p) { return "(u, v) = (" + fmt(p.x()) + ", " + fmt(p.y()) + ")"; }

std::string patchLabel(const SurfacePatch& p, int index) {
  return "patch '" + (p.name.empty() ? std::to_string(index) : p.name) + "'";
}

// Cost counters shared by every patch of one run.
struct Counters {
  long long curvature = 0;
  double curvatureSeconds = 0.0;
  long long queries = 0;
  double querySeconds = 0.0;
};

// Counts (and times) the queries the discretization and the mesher make; Mp comes from
// the surface itself (section 4.3 allows either).
class CountingControlSpace : public ControlSpace {
 public:
  CountingControlSpace(const ControlSpace& inner, const Surface& s, Counters& c) : inner_(inner), s_(s), c_(c) {}
  Metric metricAt(const Vec2& p) const override {
    const auto t0 = Clock::now();
    Metric m = inner_.metricAt(p);
    c_.querySeconds += since(t0);
    ++c_.queries;
    return m;
  }
  Mat2 parameterizationAt(const Vec2& p) const override { return parameterizationMatrix(s_, p); }
  Box2 bounds() const override { return inner_.bounds(); }

 private:
  const ControlSpace& inner_;
  const Surface& s_;
  Counters& c_;
};

const Contour& contourOf(const SurfacePatch& p, int k) {
  return k == 0 ? p.domain.outer : p.domain.holes[size_t(k - 1)];
}
int contourCount(const SurfacePatch& p) { return 1 + int(p.domain.holes.size()); }

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

std::unique_ptr<AdaptiveControlSpace> buildControlSpaceImpl(const SurfacePatch& patch,
                                                            const std::vector<Source3D>& sources3d,
                                                            const SurfaceMeshOptions& o, Counters& counters) {
  const Surface& surf = *patch.surface;
  SurfaceMetricOptions sizing = o.metric;
  require(std::isfinite(o.chordSafety) && o.chordSafety > 0.0, ErrorCode::InvalidArgument, "chordSafety must be > 0");
  sizing.chordTolerance /= o.chordSafety * o.chordSafety;
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
  auto eval = [&](const Vec2& p) {
    const auto t0 = Clock::now();
    std::optional<Metric> m = curv.tryMetricAt(p);
    counters.curvatureSeconds += since(t0);
    ++counters.curvature;
    return m;
  };

  QuadtreeOptions qo;
  qo.initialLevel = o.initialLevel;
  qo.maxLevel = o.maxLevel;
  auto cs = std::make_unique<QuadtreeControlSpace>(surf.domain(), qo);
  // Main-level grid: curvature where available, extrapolation elsewhere (section 3.1).
  for (int i = 0; i < cs->nodeCount(); ++i) {
    if (!cs->nodeIsFree(i)) continue;
    if (auto m = eval(cs->nodePosition(i)))
      cs->setNodeMetric(i, *m);
    else
      cs->clearNodeInitialized(i);
  }
  const Metric fallback = Metric::isotropic(0.1 * surf.domain().size().norm());
  extrapolateMetric(*cs, fallback);
  cs->applyConstraints();

  // Split leaves while corner metrics differ, or the analytic metric at the centre differs
  // from the bilinear value there (the average of the corners' Mt), but not below a
  // fraction of the requested size: finer leaves cannot change the mesh.
  const double thr = o.refineThreshold;
  cs->refine(
      [&](const ControlElement& e) {
        Metric corners[4];
        double hsmall = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 4; ++k) {
          corners[k] = cs->nodeMetric(e.nodes[k]);
          hsmall = std::min(hsmall, corners[k].sizes().h1);
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
        for (int i = first; i < last; ++i)
          if (cs->nodeIsFree(i))
            if (auto m = eval(cs->nodePosition(i))) cs->setNodeMetric(i, *m);
      });
  cs->applyConstraints();
  std::vector<MetricSource> sources = patch.sources;
  if (o.contourCurvature) {
    const auto contour = contourCurvatureSources(patch, sizing);
    sources.insert(sources.end(), contour.begin(), contour.end());
  }
  if (!sources.empty()) {
    DiscreteInsertionOptions io;
    io.fallbackMetric = fallback;
    insertSources(*cs, sources, io);
  }
  if (o.gradation > 0.0) {
    GradationOptions g;
    g.ratio = o.gradation;
    smoothGradation(*cs, g);
  }
  return cs;
}

// --- model bookkeeping ------------------------------------------------------------------

// One boundary curve of one patch and its current discretization (own t ascending).
struct Slot {
  int patch = 0, contour = 0, curve = 0;
  CurvePtr c;
  int minSegments = 1;
  int master = -1;  // slot discretized with this one (the "a" side), or -1
  bool masterReversed = false;
  int follower = -1;      // the "b" side when this slot is a master
  std::vector<double> t;  // parameters, 0 ... 1
  std::vector<int> gid;   // merged-mesh vertex of each point
  bool invalid = true;
};

std::string slotName(const SurfaceModel& m, const Slot& s) {
  return patchLabel(m.patches[size_t(s.patch)], s.patch) + " " + contourName(s.contour) + " curve " +
         std::to_string(s.curve);
}

// 3D point of a slot's curve at t.
Vec3 slotPoint(const SurfaceModel& m, const Slot& s, double t) {
  return m.patches[size_t(s.patch)].surface->point(s.c->point(t));
}

// Nearest-point map from 3D onto a curve of a patch: coarse table, then golden section.
class CurveProjector {
 public:
  CurveProjector(const SurfaceModel& m, const Slot& s) : m_(m), s_(s) {
    for (int i = 0; i <= kN; ++i) pts_.push_back(slotPoint(m, s, double(i) / kN));
  }
  // Parameter of the point of the curve nearest to x; *dist receives the distance.
  double project(const Vec3& x, double* dist = nullptr) const {
    int best = 0;
    double bd = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kN; ++i) {
      const double d = (pts_[size_t(i)] - x).squaredNorm();
      if (d < bd) bd = d, best = i;
    }
    double lo = double(std::max(best - 1, 0)) / kN, hi = double(std::min(best + 1, kN)) / kN;
    auto f = [&](double t) { return (slotPoint(m_, s_, t) - x).squaredNorm(); };
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double a = hi - g * (hi - lo), b = lo + g * (hi - lo), fa = f(a), fb = f(b);
    for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) {
      if (fa < fb)
        hi = b, b = a, fb = fa, a = hi - g * (hi - lo), fa = f(a);
      else
        lo = a, a = b, fa = fb, b = lo + g * (hi - lo), fb = f(b);
    }
    double t = 0.5 * (lo + hi);
    // Ends are exact matches of corners: snap when the table's end is the best.
    for (double e : {0.0, 1.0})
      if (f(e) <= f(t)) t = e;
    if (dist) *dist = std::sqrt(f(t));
    return t;
  }

 private:
  static constexpr int kN = 256;
  const SurfaceModel& m_;
  const Slot& s_;
  std::vector<Vec3> pts_;
};

double modelSize(const SurfaceModel& m) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : m.patches) {
    const Box2 b = p.surface->domain();
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) {
        const Vec3 x = p.surface->point(b.lo + Vec2(b.size().x() * i / 4.0, b.size().y() * j / 4.0));
        if (x.allFinite()) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      }
  }
  const double d = (hi - lo).norm();
  return std::isfinite(d) && d > 0 ? d : 1.0;
}

// Patch checks: domain valid, contours inside the surface's parameter box, no NaN and no
// degenerate parameterization on contours or at most of a grid of interior points.
void checkPatch(const SurfacePatch& p, int index) {
  const std::string label = patchLabel(p, index);
  require(p.surface != nullptr, ErrorCode::InvalidArgument, label + ": no surface");
  try {
    validateDomain(p.domain);
  } catch (const Error& e) {
    throw Error(e.code(), label + ": " + e.what());
  }
  const Box2 box = p.surface->domain();
  const double tol = 1e-9 * (1.0 + box.size().norm());
  auto derivs = [&](const Vec2& uv) {
    try {
      return p.surface->derivatives(uv);
    } catch (const Error& e) {
      throw Error(e.code(), label + ": " + e.what());
    }
  };
  for (int k = 0; k < contourCount(p); ++k)
    for (const Vec2& q : sampleContour(contourOf(p, k), 16)) {
      require(q.x() >= box.lo.x() - tol && q.x() <= box.hi.x() + tol && q.y() >= box.lo.y() - tol &&
                  q.y() <= box.hi.y() + tol,
              ErrorCode::InvalidDomain,
              label + ": " + contourName(k) + " leaves the surface's parameter domain [" + fmt(box.lo.x()) + ", " +
                  fmt(box.hi.x()) + "] x [" + fmt(box.lo.y()) + ", " + fmt(box.hi.y()) + "] at " + fmtUv(q));
      if (isDegenerate(derivs(q)))
        throw Error(ErrorCode::InvalidSurface,
                    label + ": degenerate parameterization (Su x Sv = 0) on " + contourName(k) + " at " + fmtUv(q));
    }
  const auto outer = sampleContour(p.domain.outer, 16);
  std::vector<std::vector<Vec2>> holes;
  for (const auto& h : p.domain.holes) holes.push_back(sampleContour(h, 16));
  int inside = 0, degenerate = 0;
  Vec2 firstBad;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      const Vec2 q = box.lo + Vec2(box.size().x() * (i + 0.5) / 12, box.size().y() * (j + 0.5) / 12);
      if (!pointInPolygon(outer, q)) continue;
      bool inHole = false;
      for (const auto& h : holes) inHole = inHole || pointInPolygon(h, q);
      if (inHole) continue;
      ++inside;
      if (isDegenerate(derivs(q)) && degenerate++ == 0) firstBad = q;
    }
  if (degenerate > 0 && 10 * degenerate > inside)
    throw Error(ErrorCode::InvalidSurface, label + ": degenerate parameterization (Su x Sv = 0) at " + fmtUv(firstBad) +
                                               " and " + std::to_string(degenerate - 1) + " more sample points");
}

// Distance between the chord x0x1 and the surface, along the surface normal at samples of
// the parameter segment u0u1 (the edge-to-surface gap, without the tangential offset a
// curved parameter line adds).
double normalChordDeviation(const Surface& s, const Vec2& u0, const Vec2& u1, const Vec3& x0, const Vec3& x1) {
  double worst = 0.0;
  for (int i = 1; i <= 7; ++i) {
    const double t = i / 8.0;
    const SurfaceDerivatives d = s.derivatives((1.0 - t) * u0 + t * u1);
    const Vec3 n = d.su.cross(d.sv);
    if (!(n.norm() > 0)) continue;
    worst = std::max(worst, std::abs(n.normalized().dot(d.p - ((1.0 - t) * x0 + t * x1))));
  }
  return worst;
}

// The same gap inside the triangle (u0, u1, u2) -> (x0, x1, x2): at the 10 interior
// barycentric points (i, j, k) / 6 (centroid included), the distance from the flat
// triangle's point to the tangent plane at the surface point of the same parameter.
double normalTriangleDeviation(const Surface& s, const Vec2 u[3], const Vec3 x[3]) {
  double worst = 0.0;
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; i + j <= 5; ++j) {
      const double a = i / 6.0, b = j / 6.0, c = 1.0 - a - b;
      const SurfaceDerivatives d = s.derivatives(a * u[0] + b * u[1] + c * u[2]);
      const Vec3 n = d.su.cross(d.sv);
      if (!(n.norm() > 0)) continue;
      worst = std::max(worst, std::abs(n.normalized().dot(d.p - (a * x[0] + b * x[1] + c * x[2]))));
    }
  return worst;
}

SegmentSource segmentSource(const Vec2& a, const Vec2& b, const Metric& m, double r) {
  SegmentSource s;
  s.a = a;
  s.b = b;
  s.metric = m;
  s.radius = r;
  return s;
}

// Flips whole patches so that elements on both sides of every shared edge traverse it in
// opposite directions (one consistent 3D orientation), starting from the first patch of
// each connected group; a patch whose sharing contradicts itself (non-orientable) is left.
// patchTriangles / patchQuads: element counts per patch, in the order of out's lists.
void orientPatches(Mesh& out, const std::vector<int>& patchTriangles, const std::vector<int>& patchQuads,
                   const std::set<std::array<int, 2>>& shared) {
  const size_t np = patchTriangles.size();
  std::vector<int> triPatch, quadPatch;
  for (size_t p = 0; p < np; ++p) {
    triPatch.insert(triPatch.end(), size_t(patchTriangles[p]), int(p));
    quadPatch.insert(quadPatch.end(), size_t(patchQuads[p]), int(p));
  }
  // For each shared edge, the (patch, +1/-1 direction) of its elements.
  std::map<std::array<int, 2>, std::vector<std::pair<int, int>>> uses;
  auto visit = [&](const int* v, int n, int patch) {
    for (int k = 0; k < n; ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      const std::array<int, 2> e{std::min(a, b), std::max(a, b)};
      if (shared.count(e)) uses[e].push_back({patch, a < b ? 1 : -1});
    }
  };
  for (size_t t = 0; t < out.triangles.size(); ++t) visit(out.triangles[t].data(), 3, triPatch[t]);
  for (size_t t = 0; t < out.quads.size(); ++t) visit(out.quads[t].data(), 4, quadPatch[t]);
  // Graph: patches p, q must flip alike (0) or oppositely (1).
  std::vector<std::vector<std::pair<int, int>>> adj(np);
  for (const auto& u : uses)
    if (u.second.size() == 2 && u.second[0].first != u.second[1].first) {
      const int differ = u.second[0].second == u.second[1].second ? 1 : 0;
      adj[size_t(u.second[0].first)].push_back({u.second[1].first, differ});
      adj[size_t(u.second[1].first)].push_back({u.second[0].first, differ});
    }
  std::vector<int> flip(np, -1);
  for (size_t s = 0; s < np; ++s) {
    if (flip[s] >= 0) continue;
    flip[s] = 0;
    std::vector<int> stack{int(s)};
    while (!stack.empty()) {
      const int p = stack.back();
      stack.pop_back();
      for (const auto& e : adj[size_t(p)])
        if (flip[size_t(e.first)] < 0) {
          flip[size_t(e.first)] = flip[size_t(p)] ^ e.second;
          stack.push_back(e.first);
        }
    }
  }
  for (size_t t = 0; t < out.triangles.size(); ++t)
    if (flip[size_t(triPatch[t])] == 1) std::swap(out.triangles[t][1], out.triangles[t][2]);
  for (size_t t = 0; t < out.quads.size(); ++t)
    if (flip[size_t(quadPatch[t])] == 1) std::swap(out.quads[t][1], out.quads[t][3]);
}

// 3D quad quality in a constant metric: min over corners of 2 |e1 x e2|_M / (|e1|_M^2 + |e2|_M^2)
// (1 for a unit square; as metricQuadQuality in the parameter plane).
double quadQuality3D(const Vec3 x[4], const Mat3& m3) {
  double q = 1.0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 e1 = x[(k + 1) % 4] - x[k], e2 = x[(k + 3) % 4] - x[k];
    const double g11 = e1.dot(m3 * e1), g22 = e2.dot(m3 * e2), g12 = e1.dot(m3 * e2);
    const double sum = g11 + g22;
    q = std::min(q, sum > 0 ? 2.0 * std::sqrt(std::max(g11 * g22 - g12 * g12, 0.0)) / sum : 0.0);
  }
  return q;
}

// All-quad split of one patch's mesh in its (u, v): each triangle into 3 quads, each quad
// into 4, one midpoint per edge. Boundary points are the first nb; the loop edge from
// boundary point i to next[i] gets its point at curveMid[i] (on the contour curve). Returns,
// for every new point, the boundary edge (i, next[i]) it splits or {-1, -1}.
std::vector<std::array<int, 2>> splitPatchIntoQuads(Mesh& pm, size_t nb, const std::vector<int>& next,
                                                    const std::vector<Vec2>& curveMid) {
  std::map<std::array<int, 2>, int> mids;
  std::vector<std::array<int, 2>> origin;
  auto addPoint = [&](const Vec2& p, std::array<int, 2> from) {
    pm.points.emplace_back(p.x(), p.y(), 0.0);
    pm.params.push_back(p);
    origin.push_back(from);
    return int(pm.params.size()) - 1;
  };
  for (size_t i = 0; i < nb; ++i)
    mids[{std::min(int(i), next[i]), std::max(int(i), next[i])}] = addPoint(curveMid[i], {int(i), next[i]});
  auto mid = [&](int a, int b) {
    const std::array<int, 2> k{std::min(a, b), std::max(a, b)};
    const auto it = mids.find(k);
    if (it != mids.end()) return it->second;
    return mids[k] = addPoint(0.5 * (pm.params[size_t(a)] + pm.params[size_t(b)]), {-1, -1});
  };
  std::vector<std::array<int, 4>> quads;
  for (const auto& t : pm.triangles) {
    const int mab = mid(t[0], t[1]), mbc = mid(t[1], t[2]), mca = mid(t[2], t[0]);
    const int g =
        addPoint((pm.params[size_t(t[0])] + pm.params[size_t(t[1])] + pm.params[size_t(t[2])]) / 3.0, {-1, -1});
    quads.push_back({t[0], mab, g, mca});
    quads.push_back({t[1], mbc, g, mab});
    quads.push_back({t[2], mca, g, mbc});
  }
  for (const auto& q : pm.quads) {
    int m[4];
    for (int k = 0; k < 4; ++k) m[k] = mid(q[size_t(k)], q[size_t((k + 1) % 4)]);
    Vec2 c = Vec2::Zero();
    for (int v : q) c += 0.25 * pm.params[size_t(v)];
    const int o = addPoint(c, {-1, -1});
    for (int k = 0; k < 4; ++k) quads.push_back({q[size_t(k)], m[k], o, m[(k + 3) % 4]});
  }
  pm.triangles.clear();
  pm.quads = std::move(quads);
  return origin;
}

// Everything one run keeps per patch.
struct PatchState {
  std::unique_ptr<AdaptiveControlSpace> cs;
  std::unique_ptr<CountingControlSpace> counted;
  std::vector<std::vector<int>> slots;  // per contour, per curve: slot index
  bool invalid = true;
  bool modified = false;
};

class ModelMesher {
 public:
  ModelMesher(const SurfaceModel& m, const SurfaceMeshOptions& o) : m_(m), o_(o) {}
  Mesh run(SurfaceMeshReport* report);

 private:
  void setupSlots();
  void validateSharing();
  void assignCornerIds();
  void discretize(int slot);
  std::vector<double> discretizeShared(const Slot& a, const Slot& b, std::vector<double>* tb);
  // Boundary loops of a patch with the merged-mesh id of every point and whether each edge lies on a shared curve.
  // curveMid (optional): per loop edge, the (u, v) of the curve at the middle parameter of the edge.
  std::vector<BoundaryLoop> loopsOf(int patch, std::vector<int>* ids, std::vector<char>* sharedEdge,
                                    std::vector<Vec2>* curveMid = nullptr) const;
  void adaptAcrossShared();
  void checkPatchBoundary(int patch);
  // Queues a source for the patch's control space (inserted by flushSources()).
  template <class S>
  void addSource(int patch, const S& s) {
    pending_[size_t(patch)].emplace_back(std::in_place_type<S>, s);
  }
  void flushSources();
  std::vector<ControlSpaceGlyph> glyphs() const;
  const ControlSpace& space(int patch) const { return *ps_[size_t(patch)].counted; }
  Vec2 uvOf(const Slot& s, size_t i) const { return s.c->point(s.t[i]); }

  const SurfaceModel& m_;
  SurfaceMeshOptions o_;
  Counters counters_;
  std::vector<Slot> slots_;
  std::vector<PatchState> ps_;
  std::vector<std::vector<MetricSource>> pending_;
  int nextId_ = 0;
  int invalidations_ = 0;
  std::vector<double> elementQuality_;
  double size_ = 1.0;
};

void ModelMesher::setupSlots() {
  ps_.resize(m_.patches.size());
  pending_.resize(m_.patches.size());
  for (size_t p = 0; p < m_.patches.size(); ++p) {
    const SurfacePatch& patch = m_.patches[p];
    for (int k = 0; k < contourCount(patch); ++k) {
      const Contour& c = contourOf(patch, k);
      ps_[p].slots.emplace_back();
      const int n = int(c.curves.size());
      for (int j = 0; j < n; ++j) {
        Slot s;
        s.patch = int(p), s.contour = k, s.curve = j;
        s.c = c.curves[size_t(j)].curve;
        s.minSegments = n == 1 ? 3 : n == 2 ? 2 : 1;
        ps_[p].slots.back().push_back(int(slots_.size()));
        slots_.push_back(std::move(s));
      }
    }
  }
  auto find = [&](const CurveRef& r, const std::string& what) {
    require(r.patch >= 0 && r.patch < int(m_.patches.size()), ErrorCode::InvalidArgument,
            what + ": no patch " + std::to_string(r.patch));
    const auto& cs = ps_[size_t(r.patch)].slots;
    require(r.contour >= 0 && r.contour < int(cs.size()), ErrorCode::InvalidArgument,
            what + ": " + patchLabel(m_.patches[size_t(r.patch)], r.patch) + " has no contour " +
                std::to_string(r.contour));
    require(r.curve >= 0 && r.curve < int(cs[size_t(r.contour)].size()), ErrorCode::InvalidArgument,
            what + ": " + patchLabel(m_.patches[size_t(r.patch)], r.patch) + " " + contourName(r.contour) +
                " has no curve " + std::to_string(r.curve));
    return cs[size_t(r.contour)][size_t(r.curve)];
  };
  for (size_t k = 0; k < m_.shared.size(); ++k) {
    const std::string what = "shared[" + std::to_string(k) + "]";
    const int a = find(m_.shared[k].a, what), b = find(m_.shared[k].b, what);
    require(a != b, ErrorCode::InvalidArgument, what + ": a curve cannot be shared with itself");
    for (int s : {a, b})
      require(slots_[size_t(s)].master < 0 && slots_[size_t(s)].follower < 0, ErrorCode::InvalidArgument,
              what + ": " + slotName(m_, slots_[size_t(s)]) + " is already shared");
    slots_[size_t(a)].follower = b;
    slots_[size_t(b)].master = a;
    slots_[size_t(b)].masterReversed = m_.shared[k].reversed;
    slots_[size_t(a)].minSegments = slots_[size_t(b)].minSegments =
        std::max(slots_[size_t(a)].minSegments, slots_[size_t(b)].minSegments);
  }
}

// Shared curves must be the same curve in 3D (sampled both ways).
void ModelMesher::validateSharing() {
  const double tol = o_.sharedTolerance * size_;
  for (const Slot& b : slots_) {
    if (b.master < 0) continue;
    const Slot& a = slots_[size_t(b.master)];
    auto mismatch = [&](const Slot& x, const Slot& y, double t, double d) {
      throw Error(ErrorCode::InvalidSurface, "shared curve mismatch: " + slotName(m_, x) + " and " + slotName(m_, y) +
                                                 " are " + fmt(d) + " apart (tolerance " + fmt(tol) +
                                                 ") at t = " + fmt(t) + ", " + fmtUv(x.c->point(t)) + " of " +
                                                 patchLabel(m_.patches[size_t(x.patch)], x.patch));
    };
    for (int end = 0; end < 2; ++end) {
      const double ta = end, tb = b.masterReversed ? 1.0 - end : double(end);
      const double d = (slotPoint(m_, a, ta) - slotPoint(m_, b, tb)).norm();
      if (d > tol) mismatch(a, b, ta, d);
    }
    const CurveProjector pa(m_, a), pb(m_, b);
    for (int i = 1; i < 16; ++i) {
      const double t = i / 16.0;
      double d;
      pb.project(slotPoint(m_, a, t), &d);
      if (d > tol) mismatch(a, b, t, d);
      pa.project(slotPoint(m_, b, t), &d);
      if (d > tol) mismatch(b, a, t, d);
    }
  }
}

// Curve ends: one merged vertex per corner, joined along contours and through sharing.
void ModelMesher::assignCornerIds() {
  const int n = int(slots_.size());
  std::vector<int> parent(size_t(2 * n));
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int x) {
    return parent[size_t(x)] == x ? x : parent[size_t(x)] = root(parent[size_t(x)]);
  };
  auto unite = [&](int x, int y) { parent[size_t(root(x))] = root(y); };
  for (size_t p = 0; p < m_.patches.size(); ++p)
    for (int k = 0; k < contourCount(m_.patches[p]); ++k) {
      const Contour& c = contourOf(m_.patches[p], k);
      const auto& ids = ps_[p].slots[size_t(k)];
      const int cnt = int(ids.size());
      for (int j = 0; j < cnt; ++j) {
        const int jn = (j + 1) % cnt;
        const int exitEnd = c.curves[size_t(j)].reversed ? 0 : 1;
        const int entryEnd = c.curves[size_t(jn)].reversed ? 1 : 0;
        unite(2 * ids[size_t(j)] + exitEnd, 2 * ids[size_t(jn)] + entryEnd);
      }
    }
  for (int s = 0; s < n; ++s) {
    const Slot& b = slots_[size_t(s)];
    if (b.master < 0) continue;
    unite(2 * b.master + 0, 2 * s + (b.masterReversed ? 1 : 0));
    unite(2 * b.master + 1, 2 * s + (b.masterReversed ? 0 : 1));
  }
  std::map<int, int> idOf;
  for (int e = 0; e < 2 * n; ++e)
    if (!idOf.count(root(e))) idOf[root(e)] = nextId_++;
  for (int s = 0; s < n; ++s) slots_[size_t(s)].gid = {idOf[root(2 * s)], idOf[root(2 * s + 1)]};
}

// Shared curve: per piece of a (between its corners), the metric length density is the
// larger of the two patches' at each sample (stricter metric); points at equal length.
std::vector<double> ModelMesher::discretizeShared(const Slot& a, const Slot& b, std::vector<double>* tb) {
  const CurveProjector proj(m_, b);
  const ControlSpace& csa = space(a.patch);
  const ControlSpace& csb = space(b.patch);
  std::vector<double> bounds{0.0};
  for (double t : a.c->breakpoints())
    if (t > bounds.back() && t < 1.0) bounds.push_back(t);
  bounds.push_back(1.0);
  auto mapB = [&](double t) { return proj.project(slotPoint(m_, a, t)); };

  std::vector<double> ts{0.0};
  int pieceSegments = 0;
  std::vector<std::vector<double>> pieceT, pieceCum;
  for (size_t k = 0; k + 1 < bounds.size(); ++k) {
    int samples = 32;
    std::vector<double> t, cum;
    for (int pass = 0; pass < 2; ++pass) {
      t.assign(size_t(samples + 1), 0.0);
      cum.assign(size_t(samples + 1), 0.0);
      Vec2 ua = a.c->point(bounds[k]), ub = b.c->point(mapB(bounds[k]));
      for (int i = 0; i <= samples; ++i) {
        t[size_t(i)] = bounds[k] + (bounds[k + 1] - bounds[k]) * i / samples;
        if (i == 0) continue;
        const Vec2 na = a.c->point(t[size_t(i)]), nb = b.c->point(mapB(t[size_t(i)]));
        const double la = csa.metricAt(0.5 * (ua + na)).length(na - ua);
        const double lb = csb.metricAt(0.5 * (ub + nb)).length(nb - ub);
        cum[size_t(i)] = cum[size_t(i - 1)] + std::max(la, lb);
        ua = na, ub = nb;
      }
      const double len = cum.back();
      require(std::isfinite(len), ErrorCode::InvalidMetric, "metric length of " + slotName(m_, a) + " is not finite");
      const int want = int(std::min(20000.0, std::ceil(8.0 * len)));
      if (want <= samples) break;
      samples = want;
    }
    pieceSegments += int(std::max(1.0, std::round(cum.back())));
    pieceT.push_back(std::move(t));
    pieceCum.push_back(std::move(cum));
  }
  const int extra = std::max(0, a.minSegments - pieceSegments);
  for (size_t k = 0; k < pieceT.size(); ++k) {
    const auto& t = pieceT[k];
    const auto& cum = pieceCum[k];
    int n = int(std::max(1.0, std::round(cum.back())));
    if (k == 0) n += extra;
    require(std::int64_t(n) <= o_.mesher.maxElements, ErrorCode::ElementBudgetExceeded,
            "discretizing " + slotName(m_, a) + " exceeds the element budget");
    size_t j = 1;
    for (int i = 1; i < n; ++i) {
      const double target = cum.back() * i / n;
      while (j + 1 < cum.size() && cum[j] < target) ++j;
      const double w = cum[j] > cum[j - 1] ? (target - cum[j - 1]) / (cum[j] - cum[j - 1]) : 0.5;
      ts.push_back(std::max(ts.back(), t[j - 1] + w * (t[j] - t[j - 1])));
    }
    ts.push_back(bounds[k + 1]);
  }
  tb->clear();
  for (size_t i = 0; i < ts.size(); ++i) {
    if (i == 0 || i + 1 == ts.size())
      tb->push_back((i == 0) != b.masterReversed ? 0.0 : 1.0);
    else
      tb->push_back(mapB(ts[i]));
  }
  return ts;
}

void ModelMesher::discretize(int si) {
  Slot& s = slots_[size_t(si)];
  const int first = s.gid.front(), last = s.gid.back();
  std::vector<int> gid{first};
  if (s.follower < 0) {
    DiscretizeOptions d;
    d.maxSegments = std::max<std::int64_t>(1, o_.mesher.maxElements);
    s.t = discretizeCurve(*s.c, space(s.patch), s.minSegments, d);
  } else {
    Slot& b = slots_[size_t(s.follower)];
    std::vector<double> tb;
    s.t = discretizeShared(s, b, &tb);
    const int bFirst = b.gid.front(), bLast = b.gid.back();
    b.gid.clear();
    std::vector<int> inner;
    for (size_t i = 1; i + 1 < s.t.size(); ++i) inner.push_back(nextId_ + int(i) - 1);
    std::vector<double> bt = tb;
    std::vector<int> bid{b.masterReversed ? bLast : bFirst};
    bid.insert(bid.end(), inner.begin(), inner.end());
    bid.push_back(b.masterReversed ? bFirst : bLast);
    if (b.masterReversed) {
      std::reverse(bt.begin(), bt.end());
      std::reverse(bid.begin(), bid.end());
    }
    // b's ends keep their own corner ids (same corners by construction).
    bid.front() = bFirst, bid.back() = bLast;
    b.t = bt;
    b.gid = bid;
    b.invalid = false;
  }
  for (size_t i = 1; i + 1 < s.t.size(); ++i) gid.push_back(nextId_++);
  gid.push_back(last);
  s.gid = gid;
  s.invalid = false;
}

std::vector<BoundaryLoop> ModelMesher::loopsOf(int p, std::vector<int>* ids, std::vector<char>* sharedEdge,
                                               std::vector<Vec2>* curveMid) const {
  const SurfacePatch& patch = m_.patches[size_t(p)];
  std::vector<BoundaryLoop> loops;
  for (int k = 0; k < contourCount(patch); ++k) {
    const Contour& c = contourOf(patch, k);
    BoundaryLoop loop;
    std::vector<int> lid;
    std::vector<char> lsh;
    std::vector<Vec2> lmid;
    for (size_t j = 0; j < c.curves.size(); ++j) {
      const Slot& s = slots_[size_t(ps_[size_t(p)].slots[size_t(k)][j])];
      const bool rev = c.curves[j].reversed;
      const size_t n = s.t.size();
      for (size_t i = 0; i + 1 < n; ++i) {
        const size_t q = rev ? n - 1 - i : i;
        loop.points.push_back(uvOf(s, q));
        lid.push_back(s.gid[q]);
        loop.edgeRefs.push_back(s.c->ref());
        lsh.push_back(s.master >= 0 || s.follower >= 0);
        lmid.push_back(s.c->point(0.5 * (s.t[q] + s.t[rev ? q - 1 : q + 1])));
      }
    }
    const bool ccw = signedArea(loop.points) > 0;
    if (ccw != (k == 0)) {
      const size_t n = loop.points.size();
      BoundaryLoop rev;
      std::vector<int> rid;
      std::vector<char> rsh;
      std::vector<Vec2> rmid;
      for (size_t i = 0; i < n; ++i) {
        rev.points.push_back(loop.points[n - 1 - i]);
        rid.push_back(lid[n - 1 - i]);
        const size_t e = (2 * n - 2 - i) % n;
        rev.edgeRefs.push_back(loop.edgeRefs[e]);
        rsh.push_back(lsh[e]);
        rmid.push_back(lmid[e]);
      }
      loop = std::move(rev);
      lid = std::move(rid);
      lsh = std::move(rsh);
      lmid = std::move(rmid);
    }
    if (ids) ids->insert(ids->end(), lid.begin(), lid.end());
    if (sharedEdge) sharedEdge->insert(sharedEdge->end(), lsh.begin(), lsh.end());
    if (curveMid) curveMid->insert(curveMid->end(), lmid.begin(), lmid.end());
    loops.push_back(std::move(loop));
  }
  return loops;
}

// Each patch takes its neighbour's metric at the shared points, converted through the
// Jacobians (neighbour (u, v) -> 3D tangent metric -> own (u, v)), as node sources.
void ModelMesher::adaptAcrossShared() {
  for (const Slot& a : slots_) {
    if (a.follower < 0) continue;
    const Slot& b = slots_[size_t(a.follower)];
    const Surface& sa = *m_.patches[size_t(a.patch)].surface;
    const Surface& sb = *m_.patches[size_t(b.patch)].surface;
    NodeSource toA, toB;
    const size_t n = a.t.size();
    for (size_t i = 0; i < n; ++i) {
      const size_t ib = b.masterReversed ? n - 1 - i : i;
      const Vec2 ua = uvOf(a, i), ub = uvOf(b, ib);
      const SurfaceDerivatives da = sa.derivatives(ua), db = sb.derivatives(ub);
      if (isDegenerate(da) || isDegenerate(db)) continue;
      const Mat3 ma = metric3DFromParameter(space(a.patch).metricAt(ua), da);
      const Mat3 mb = metric3DFromParameter(space(b.patch).metricAt(ub), db);
      toA.points.push_back(ua);
      toA.metrics.push_back(pullBackMetric(mb, da));
      toB.points.push_back(ub);
      toB.metrics.push_back(pullBackMetric(ma, db));
    }
    if (!toA.points.empty()) addSource(a.patch, std::move(toA));
    if (!toB.points.empty()) addSource(b.patch, std::move(toB));
  }
}

void ModelMesher::flushSources() {
  for (size_t p = 0; p < ps_.size(); ++p) {
    if (pending_[p].empty()) continue;
    insertSources(*ps_[p].cs, pending_[p]);
    if (o_.gradation > 0.0) {
      GradationOptions g;
      g.ratio = o_.gradation;
      smoothGradation(*ps_[p].cs, g);
    }
    pending_[p].clear();
    ps_[p].modified = true;
  }
}

// Section 3.2 on one patch after its boundary-only triangulation: proximity of boundaries
// (eps2), contour chords (curvature of the contour in 3D), boundary segment lengths (eps1).
void ModelMesher::checkPatchBoundary(int p) {
  const SurfacePatch& patch = m_.patches[size_t(p)];
  const Surface& surf = *patch.surface;
  const ControlSpace& cs = space(p);
  PlanarMesherOptions bo = o_.mesher;
  bo.boundaryOnly = true;
  bo.timings = nullptr;
  bo.progress = nullptr;
  const Mesh bm = meshPlanarBoundary(loopsOf(p, nullptr, nullptr), cs, bo);

  // Boundary vicinity (eps2 = 0.2): a triangle of small metric area whose vertex lies
  // within half a unit (metric) of the opposite boundary edge joins two boundary pieces
  // that are closer than the metric asks. Fans onto finely split edges and ears of a
  // contour (two boundary edges) are not proximity.
  std::set<std::array<int, 2>> bedges;
  for (const auto& e : bm.edges) bedges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  auto uvAt = [&](int i) { return bm.params.empty() ? Vec2(bm.points[size_t(i)].head<2>()) : bm.params[size_t(i)]; };
  for (const auto& tri : bm.triangles) {
    int onBoundary = 0, boundaryEdge = -1;
    for (int k = 0; k < 3; ++k) {
      const int i0 = tri[size_t(k)], i1 = tri[size_t((k + 1) % 3)];
      if (bedges.count({std::min(i0, i1), std::max(i0, i1)})) ++onBoundary, boundaryEdge = k;
    }
    if (onBoundary > 1) continue;
    const Vec2 a = uvAt(tri[0]), b = uvAt(tri[1]), c = uvAt(tri[2]);
    const Vec2 g = (a + b + c) / 3.0;
    const Metric m = cs.metricAt(g);
    const Vec2 e[3] = {m.apply(b - a), m.apply(c - b), m.apply(a - c)};
    const double area = 0.5 * std::abs(e[0].x() * e[1].y() - e[0].y() * e[1].x());
    if (!(area < 0.2)) continue;
    double gap;  // metric distance between the boundary pieces the triangle joins
    if (boundaryEdge >= 0)
      gap = 2.0 * area / e[boundaryEdge].norm();
    else
      gap = 2.0 * area / std::max({e[0].norm(), e[1].norm(), e[2].norm()});
    if (gap < 0.5) {
      const double uvLongest = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
      RadialSource src;
      src.center = g;
      src.metric = m.scaled(std::max(gap / 0.5, 0.25));
      src.radius = 0.5 * uvLongest;
      addSource(p, src);
    }
  }

  const double tol = o_.metric.chordTolerance;
  for (const auto& contourSlots : ps_[size_t(p)].slots)
    for (int si : contourSlots) {
      Slot& s = slots_[size_t(si)];
      const Slot* other = s.master >= 0     ? &slots_[size_t(s.master)]
                          : s.follower >= 0 ? &slots_[size_t(s.follower)]
                                            : nullptr;
      const int owner = s.master >= 0 ? s.master : si;  // the slot that gets re-discretized
      const size_t n = s.t.size();
      for (size_t i = 0; i + 1 < n; ++i) {
        const Vec2 u0 = uvOf(s, i), u1 = uvOf(s, i + 1), um = 0.5 * (u0 + u1);
        const double l = cs.metricAt(um).length(u1 - u0);
        double lOther = 0.0;
        if (other) {
          const size_t j =
              (s.master >= 0 ? s.masterReversed : slots_[size_t(s.follower)].masterReversed) ? n - 1 - i : i;
          const size_t j1 =
              (s.master >= 0 ? s.masterReversed : slots_[size_t(s.follower)].masterReversed) ? j - 1 : j + 1;
          const Vec2 v0 = uvOf(*other, j), v1 = uvOf(*other, j1);
          lOther = space(other->patch).metricAt(0.5 * (v0 + v1)).length(v1 - v0);
        }
        // Contour chord: the 3D chord against the 3D contour at the segment's middle parameter.
        const Vec3 x0 = surf.point(u0), x1 = surf.point(u1);
        const double tm = 0.5 * (s.t[i] + s.t[i + 1]);
        const Vec3 xm = surf.point(s.c->point(tm));
        const double dev = (xm - 0.5 * (x0 + x1)).norm();
        if (tol > 0 && dev > tol) {
          const double h = 0.9 * (u1 - u0).norm() * std::sqrt(tol / dev);
          const Vec2 d = u1 - u0;
          addSource(p,
                    segmentSource(u0, u1, Metric::fromSizes(pm::atan2(d.y(), d.x()), h, o_.metric.maxAspectRatio * h),
                                  0.5 * d.norm()));
          slots_[size_t(owner)].invalid = true;
        }
        // Segment length (eps1 = 0.8): refine near short segments, unless without adaptation
        // the shortness only comes from the neighbour's stricter metric.
        const bool neighbourMadeIt = other && lOther > l;
        // The segment's length is the reference along it; across it the metric stays as it is.
        if (l < 0.8 && (o_.adaptation || !neighbourMadeIt)) {
          const Vec2 d = u1 - u0;
          const Metric here = cs.metricAt(um);
          const double across = here.sizeAlong(Vec2(-d.y(), d.x()));
          addSource(
              p, segmentSource(u0, u1, Metric::fromSizes(pm::atan2(d.y(), d.x()), d.norm(), std::max(across, d.norm())),
                               0.25 * d.norm()));
        }
        const double lEff = std::max(l, lOther);
        if ((lEff < 0.5 && n > 2 && std::max<size_t>(n - 1, 1) > size_t(s.minSegments)) || lEff > 2.0)
          slots_[size_t(owner)].invalid = true;
      }
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
      const Mat2 inv = cand.m.transform().inverse();
      ControlSpaceGlyph g;
      g.patch = int(p);
      for (int k = 0; k < 24; ++k) {
        const double a = 6.283185307179586 * k / 24;
        const Vec2 uv = cand.c + 0.5 * (inv * Vec2(pm::cos(a), pm::sin(a)));
        g.uv.push_back(uv);
        g.xyz.push_back(patch.surface->point(uv.cwiseMax(dom.lo).cwiseMin(dom.hi)));
      }
      out.push_back(std::move(g));
    }
  }
  return out;
}

Mesh ModelMesher::run(SurfaceMeshReport* report) {
  const auto t0 = Clock::now();
  require(!m_.patches.empty(), ErrorCode::InvalidArgument, "surface model: no patch");
  validate(o_.metric);
  for (size_t p = 0; p < m_.patches.size(); ++p) checkPatch(m_.patches[p], int(p));
  size_ = modelSize(m_);
  setupSlots();
  validateSharing();
  assignCornerIds();

  // 1-2: initial control spaces, every contour invalid.
  for (size_t p = 0; p < m_.patches.size(); ++p) {
    try {
      ps_[p].cs = buildControlSpaceImpl(m_.patches[p], m_.sources3d, o_, counters_);
    } catch (const Error& e) {
      throw Error(e.code(), patchLabel(m_.patches[p], int(p)) + ": " + e.what());
    }
    ps_[p].counted = std::make_unique<CountingControlSpace>(*ps_[p].cs, *m_.patches[p].surface, counters_);
  }

  // 4-13: discretize invalid contours, check patches, update control spaces.
  int round = 0;
  for (; round < std::max(1, o_.maxRounds); ++round) {
    bool any = false;
    for (size_t s = 0; s < slots_.size(); ++s)
      if (slots_[s].invalid && slots_[s].master < 0) {
        ps_[size_t(slots_[s].patch)].invalid = true;
        if (slots_[s].follower >= 0) ps_[size_t(slots_[size_t(slots_[s].follower)].patch)].invalid = true;
        discretize(int(s));
        any = true;
        if (round > 0) ++invalidations_;
      }
    if (!any) break;
    if (round == 0 && o_.adaptation) {
      adaptAcrossShared();
      flushSources();
    }
    for (size_t p = 0; p < ps_.size(); ++p)
      if (ps_[p].invalid) {
        try {
          checkPatchBoundary(int(p));
        } catch (const Error& e) {
          throw Error(e.code(), patchLabel(m_.patches[p], int(p)) + ": " + e.what());
        }
        ps_[p].invalid = false;
      }
    flushSources();
  }

  // 14-16: inner nodes and improvement per patch; merge.
  Mesh out;
  out.dimension = 3;
  std::vector<int> defined(size_t(nextId_), -1);  // patch that placed each merged boundary vertex
  out.points.resize(size_t(nextId_));
  out.params.resize(size_t(nextId_));
  Surface3DQuality q;
  std::set<std::array<int, 2>> seenEdges, sharedEdges;
  double lenSum = 0.0, qSum = 0.0;
  int triCount = 0, within = 0;
  q.edgeLengthMin = q.qualityMin = std::numeric_limits<double>::infinity();
  std::vector<int> patchTriangles, patchQuads;
  std::vector<double> triQuality, quadQuality;
  std::map<std::array<int, 2>, int> boundaryMid;  // all-quad: merged point splitting a contour edge
  for (size_t p = 0; p < m_.patches.size(); ++p) {
    const SurfacePatch& patch = m_.patches[p];
    const Surface& surf = *patch.surface;
    const ControlSpace& cs = space(int(p));
    std::vector<int> ids;
    std::vector<char> shared;
    std::vector<Vec2> curveMid;
    const auto loops = loopsOf(int(p), &ids, &shared, &curveMid);
    PlanarMesherOptions mo = o_.mesher;
    mo.boundaryOnly = false;
    // Quads are merged in the patch's (u, v) (never across its contour edges); the all-quad
    // split is done here so that shared contour edges get one midpoint for both patches.
    mo.quads = o_.quads || o_.allQuads;
    mo.allQuads = false;
    Mesh pm;
    try {
      pm = meshPlanarBoundary(loops, cs, mo);
    } catch (const Error& e) {
      throw Error(e.code(), patchLabel(patch, int(p)) + ": " + e.what());
    }
    const size_t nb = ids.size();
    if (pm.params.size() != pm.points.size()) {  // (the planar mesher fills params; keep the fallback)
      pm.params.clear();
      for (const Vec3& x : pm.points) pm.params.push_back(x.head<2>());
    }
    // Loop edges: boundary point i to next[i].
    std::vector<int> next(nb);
    {
      size_t base = 0;
      for (const auto& loop : loops) {
        const size_t n = loop.points.size();
        for (size_t i = 0; i < n; ++i) next[base + i] = int(base + (i + 1) % n);
        base += n;
      }
    }
    // A merged quad is not flat: where its two triangulations leave the surface by more
    // than the chord tolerance, the merge is undone (the pair it came from, diagonal 1-3),
    // so quad-dominant meshes keep the tolerance the triangles were sized for.
    if (!pm.quads.empty() && o_.metric.chordTolerance > 0) {
      std::vector<std::array<int, 4>> kept;
      for (const auto& qd : pm.quads) {
        Vec2 u[4];
        Vec3 x[4];
        for (int k = 0; k < 4; ++k) u[k] = pm.params[size_t(qd[size_t(k)])], x[k] = surf.point(u[k]);
        double dev = 0.0;
        for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}, std::array<int, 3>{0, 1, 3},
                                std::array<int, 3>{1, 2, 3}}) {
          const Vec2 tu[3] = {u[tri[0]], u[tri[1]], u[tri[2]]};
          const Vec3 tx[3] = {x[tri[0]], x[tri[1]], x[tri[2]]};
          dev = std::max(dev, normalTriangleDeviation(surf, tu, tx));
        }
        if (dev <= o_.metric.chordTolerance) {
          kept.push_back(qd);
        } else {
          pm.triangles.push_back({qd[0], qd[1], qd[3]});
          pm.triangles.push_back({qd[1], qd[2], qd[3]});
        }
      }
      pm.quads = std::move(kept);
    }
    const size_t nBefore = pm.params.size();
    std::vector<std::array<int, 2>> splits;
    if (o_.allQuads) splits = splitPatchIntoQuads(pm, nb, next, curveMid);
    std::vector<int> gid(pm.params.size());
    for (size_t i = 0; i < pm.params.size(); ++i) {
      const Vec2 uv = pm.params[i];
      int g = -1;
      const std::array<int, 2> from = i >= nBefore ? splits[i - nBefore] : std::array<int, 2>{-1, -1};
      std::array<int, 2> key{-1, -1};
      if (from[0] >= 0 && o_.mergeMesh) {
        key = {std::min(ids[size_t(from[0])], ids[size_t(from[1])]),
               std::max(ids[size_t(from[0])], ids[size_t(from[1])])};
        const auto it = boundaryMid.find(key);
        if (it != boundaryMid.end()) g = it->second;
      }
      if (i < nb && o_.mergeMesh)
        g = ids[i];
      else if (g < 0) {
        g = int(out.points.size());
        out.points.emplace_back();
        out.params.emplace_back();
        defined.push_back(-1);
        if (key[0] >= 0) boundaryMid[key] = g;
      }
      gid[i] = g;
      if (defined[size_t(g)] < 0) {
        const Vec3 x = surf.point(uv);
        require(x.allFinite(), ErrorCode::InvalidSurface,
                patchLabel(patch, int(p)) + ": S(u, v) is NaN or infinite at " + fmtUv(uv));
        out.points[size_t(g)] = x;
        out.params[size_t(g)] = uv;
        defined[size_t(g)] = int(p);
      }
    }
    // Boundary edges (split in two for all-quad): shared ones are interior to the merged mesh.
    {
      std::map<std::array<int, 2>, int> localMid;
      for (size_t k = 0; k < splits.size(); ++k)
        if (splits[k][0] >= 0) localMid[splits[k]] = int(nBefore + k);
      size_t base = 0;
      for (const auto& loop : loops) {
        const size_t n = loop.points.size();
        for (size_t i = 0; i < n; ++i) {
          std::vector<int> chain{gid[base + i]};
          const auto it = localMid.find({int(base + i), next[base + i]});
          if (it != localMid.end()) chain.push_back(gid[size_t(it->second)]);
          chain.push_back(gid[size_t(next[base + i])]);
          for (size_t c = 0; c + 1 < chain.size(); ++c) {
            const int a = chain[c], b = chain[c + 1];
            const std::array<int, 2> e{std::min(a, b), std::max(a, b)};
            if (shared[base + i] && o_.mergeMesh)
              sharedEdges.insert(e);
            else {
              out.edges.push_back({a, b});
              out.edgeRefs.push_back(loop.edgeRefs[i]);
            }
          }
        }
        base += n;
      }
    }
    auto uvOfLocal = [&](int i) { return pm.params[size_t(i)]; };
    auto metric3 = [&](const Vec2& uv) {
      const SurfaceDerivatives d = surf.derivatives(uv);
      return metric3DFromParameter(cs.metricAt(uv), d);
    };
    // Edge statistics once per merged edge.
    auto measureEdge = [&](int i0, int i1) {
      const int g0 = gid[size_t(i0)], g1 = gid[size_t(i1)];
      if (!seenEdges.insert({std::min(g0, g1), std::max(g0, g1)}).second) return;
      const Vec2 u0 = uvOfLocal(i0), u1 = uvOfLocal(i1);
      const Vec3& x0 = out.points[size_t(g0)];
      const Vec3& x1 = out.points[size_t(g1)];
      const double l = (edgeLength3D(x0, x1, metric3(u0)) + 4.0 * edgeLength3D(x0, x1, metric3(0.5 * (u0 + u1))) +
                        edgeLength3D(x0, x1, metric3(u1))) /
                       6.0;
      lenSum += l;
      q.edgeLengthMin = std::min(q.edgeLengthMin, l);
      q.edgeLengthMax = std::max(q.edgeLengthMax, l);
      if (l >= std::sqrt(0.5) && l <= std::sqrt(2.0)) ++within;
      ChordDeviationOptions co;
      co.samples = 7;
      q.isoChordDeviationMax = std::max(q.isoChordDeviationMax, chordDeviation(surf, u0, u1, co));
      q.edgeChordDeviationMax = std::max(q.edgeChordDeviationMax, normalChordDeviation(surf, u0, u1, x0, x1));
      ++q.edges;
    };
    for (const auto& t : pm.triangles) {
      const std::array<int, 3> g{gid[size_t(t[0])], gid[size_t(t[1])], gid[size_t(t[2])]};
      out.triangles.push_back(g);
      out.triangleRefs.push_back(patch.id);
      if (!o_.measureQuality) continue;
      const Vec2 a = uvOfLocal(t[0]), b = uvOfLocal(t[1]), c = uvOfLocal(t[2]);
      const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (!(area > 0)) ++q.inverted;
      const Vec2 tu[3] = {a, b, c};
      const Vec3 tx[3] = {out.points[size_t(g[0])], out.points[size_t(g[1])], out.points[size_t(g[2])]};
      q.chordDeviationMax = std::max(q.chordDeviationMax, normalTriangleDeviation(surf, tu, tx));
      const double qq = triangleQuality3D(tx[0], tx[1], tx[2], metric3((a + b + c) / 3.0));
      qSum += qq;
      triQuality.push_back(qq);
      q.qualityMin = std::min(q.qualityMin, qq);
      ++triCount;
      for (int k = 0; k < 3; ++k) measureEdge(t[size_t(k)], t[size_t((k + 1) % 3)]);
    }
    for (const auto& t : pm.quads) {
      const std::array<int, 4> g{gid[size_t(t[0])], gid[size_t(t[1])], gid[size_t(t[2])], gid[size_t(t[3])]};
      out.quads.push_back(g);
      out.quadRefs.push_back(patch.id);
      if (!o_.measureQuality) continue;
      Vec2 tu[4];
      Vec3 tx[4];
      for (int k = 0; k < 4; ++k) tu[k] = uvOfLocal(t[size_t(k)]), tx[k] = out.points[size_t(g[size_t(k)])];
      // Inverted: a corner turning clockwise in (u, v) (non-convex or clockwise quad).
      bool convex = true;
      for (int k = 0; k < 4; ++k) {
        const Vec2 e1 = tu[(k + 1) % 4] - tu[k], e0 = tu[k] - tu[(k + 3) % 4];
        convex = convex && e0.x() * e1.y() - e0.y() * e1.x() > 0;
      }
      if (!convex) ++q.inverted;
      // Chord deviation over the two triangles (0, 1, 2), (0, 2, 3) of the flat-split quad.
      for (int d = 0; d < 2; ++d) {
        const Vec2 su[3] = {tu[0], tu[1 + d], tu[2 + d]};
        const Vec3 sx[3] = {tx[0], tx[1 + d], tx[2 + d]};
        q.chordDeviationMax = std::max(q.chordDeviationMax, normalTriangleDeviation(surf, su, sx));
      }
      const double qq = quadQuality3D(tx, metric3(0.25 * (tu[0] + tu[1] + tu[2] + tu[3])));
      qSum += qq;
      quadQuality.push_back(qq);
      q.qualityMin = std::min(q.qualityMin, qq);
      ++triCount;
      for (int k = 0; k < 4; ++k) measureEdge(t[size_t(k)], t[size_t((k + 1) % 4)]);
    }
    patchTriangles.push_back(int(pm.triangles.size()));
    patchQuads.push_back(int(pm.quads.size()));
  }
  elementQuality_ = triQuality;
  elementQuality_.insert(elementQuality_.end(), quadQuality.begin(), quadQuality.end());
  q.edgesWithinSqrt2 = q.edges ? double(within) / q.edges : 0.0;
  q.edgeLengthMean = q.edges ? lenSum / q.edges : 0.0;
  q.qualityMean = triCount ? qSum / triCount : 0.0;
  if (!q.edges) q.edgeLengthMin = 0.0;
  if (!triCount) q.qualityMin = 0.0;
  q.chordDeviationMax = std::max(q.chordDeviationMax, q.edgeChordDeviationMax);
  q.chordDeviationMaxRelative = o_.metric.chordTolerance > 0 ? q.chordDeviationMax / o_.metric.chordTolerance : 0.0;
  if (o_.consistentOrientation) orientPatches(out, patchTriangles, patchQuads, sharedEdges);
  // Drop merged ids left over from earlier discretizations (never placed).
  {
    std::vector<int> remap(out.points.size(), -1);
    std::vector<Vec3> pts;
    std::vector<Vec2> prm;
    for (size_t i = 0; i < out.points.size(); ++i)
      if (defined[i] >= 0) {
        remap[i] = int(pts.size());
        pts.push_back(out.points[i]);
        prm.push_back(out.params[i]);
      }
    out.points = std::move(pts);
    out.params = std::move(prm);
    for (auto& t : out.triangles)
      for (int& v : t) v = remap[size_t(v)];
    for (auto& t : out.quads)
      for (int& v : t) v = remap[size_t(v)];
    for (auto& e : out.edges)
      for (int& v : e) v = remap[size_t(v)];
    std::set<std::array<int, 2>> se;
    for (const auto& e : sharedEdges) {
      const int a = remap[size_t(e[0])], b = remap[size_t(e[1])];
      se.insert({std::min(a, b), std::max(a, b)});
    }
    sharedEdges = std::move(se);
  }
  out.pointRefs.assign(out.points.size(), 0);

  if (report) {
    report->elementQuality = elementQuality_;
    if (o_.controlSpaceGlyphs) report->controlSpaceGlyphs = glyphs();
    report->patches = int(m_.patches.size());
    report->rounds = round;
    report->invalidations = invalidations_;
    report->vertices = out.vertexCount();
    report->triangles = int(out.triangles.size());
    report->sharedEdgeList.assign(sharedEdges.begin(), sharedEdges.end());
    report->sharedEdges = int(sharedEdges.size());
    report->crossSharedSizeRatioMax = acrossEdgeSizeRatio(out, report->sharedEdgeList);
    report->quality = q;
    report->curvatureEvaluations = counters_.curvature;
    report->curvatureSeconds = counters_.curvatureSeconds;
    report->controlSpaceQueries = counters_.queries;
    report->controlSpaceSeconds = counters_.querySeconds;
    report->patchTriangles = patchTriangles;
    report->secondsTotal = since(t0);
  }
  return out;
}

}  // namespace

Mat3 metric3DFromParameter(const Metric& m, const SurfaceDerivatives& d) {
  const Eigen::Matrix<double, 3, 2> j = d.jacobian();
  const Mat2 g = j.transpose() * j;
  const Eigen::Matrix<double, 2, 3> jp = g.inverse() * j.transpose();  // J+: 3D tangent vector -> (u, v)
  Mat3 t = jp.transpose() * m.tensor() * jp;
  t = 0.5 * (t + t.transpose());
  const Vec3 n = d.su.cross(d.sv);
  if (n.norm() > 0) {
    const double lmax = Eigen::SelfAdjointEigenSolver<Mat3>(t, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
    const Vec3 nu = n.normalized();
    t += lmax * nu * nu.transpose();
  }
  return t;
}

double acrossEdgeSizeRatio(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges) {
  // Elements: triangles, then quads (index nt + q).
  const size_t nt = mesh.triangles.size();
  std::map<std::array<int, 2>, std::vector<int>> at;
  for (const auto& e : edges) at[{std::min(e[0], e[1]), std::max(e[0], e[1])}];
  auto visit = [&](const int* v, int n, int element) {
    for (int k = 0; k < n; ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      auto it = at.find({std::min(a, b), std::max(a, b)});
      if (it != at.end()) it->second.push_back(element);
    }
  };
  for (size_t t = 0; t < nt; ++t) visit(mesh.triangles[t].data(), 3, int(t));
  for (size_t t = 0; t < mesh.quads.size(); ++t) visit(mesh.quads[t].data(), 4, int(nt + t));
  auto triArea = [&](int i, int j, int k) {
    const Vec3& a = mesh.points[size_t(i)];
    return 0.5 * (mesh.points[size_t(j)] - a).cross(mesh.points[size_t(k)] - a).norm();
  };
  auto area = [&](int e) {
    if (size_t(e) < nt) {
      const auto& t = mesh.triangles[size_t(e)];
      return triArea(t[0], t[1], t[2]);
    }
    const auto& q = mesh.quads[size_t(e) - nt];
    return triArea(q[0], q[1], q[2]) + triArea(q[0], q[2], q[3]);
  };
  double worst = 0.0;
  for (const auto& e : at)
    if (e.second.size() == 2) {
      const double s0 = std::sqrt(area(e.second[0])), s1 = std::sqrt(area(e.second[1]));
      if (s0 > 0 && s1 > 0) worst = std::max(worst, std::max(s0, s1) / std::min(s0, s1));
    }
  return worst;
}

std::vector<std::array<int, 2>> openEdges(const Mesh& mesh) {
  std::map<std::array<int, 2>, int> count;
  auto visit = [&](const int* v, int n) {
    for (int k = 0; k < n; ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  };
  for (const auto& t : mesh.triangles) visit(t.data(), 3);
  for (const auto& q : mesh.quads) visit(q.data(), 4);
  std::vector<std::array<int, 2>> out;
  for (const auto& e : count)
    if (e.second == 1) out.push_back(e.first);
  return out;
}

std::unique_ptr<AdaptiveControlSpace> buildPatchControlSpace(const SurfacePatch& patch,
                                                             const std::vector<Source3D>& sources3d,
                                                             const SurfaceMeshOptions& options) {
  validate(options.metric);
  Counters c;
  return buildControlSpaceImpl(patch, sources3d, options, c);
}

Mesh meshSurfaceModel(const SurfaceModel& model, const SurfaceMeshOptions& options, SurfaceMeshReport* report) {
  ModelMesher mesher(model, options);
  return mesher.run(report);
}

Mesh meshSurfacePatch(const SurfacePatch& patch, const SurfaceMeshOptions& options, SurfaceMeshReport* report) {
  SurfaceModel m;
  m.patches.push_back(patch);
  return meshSurfaceModel(m, options, report);
}

}  // namespace anisomesh

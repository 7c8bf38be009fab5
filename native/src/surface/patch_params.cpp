#include "anisomesh/surface/patch_params.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "model_mesher.h"

namespace anisomesh {

std::vector<int> elementPatches(const SurfaceModel& model, const Mesh& mesh) {
  std::map<int, int> byId;
  for (size_t p = 0; p < model.patches.size(); ++p) byId.emplace(model.patches[p].id, int(p));
  // Neighbouring elements mostly share their reference: the last lookup is kept.
  int lastRef = 0, lastPatch = -2;
  auto patchOf = [&](const std::vector<int>& refs, size_t e) {
    if (e >= refs.size()) return -1;
    if (lastPatch != -2 && refs[e] == lastRef) return lastPatch;
    const auto it = byId.find(refs[e]);
    lastRef = refs[e];
    lastPatch = it == byId.end() ? -1 : it->second;
    return lastPatch;
  };
  std::vector<int> out;
  out.reserve(mesh.triangles.size() + mesh.quads.size());
  for (size_t e = 0; e < mesh.triangles.size(); ++e) out.push_back(patchOf(mesh.triangleRefs, e));
  for (size_t e = 0; e < mesh.quads.size(); ++e) out.push_back(patchOf(mesh.quadRefs, e));
  return out;
}

namespace {

// The parameter of a curve where dist2 is least: the best of samplesPerCurve + 1 samples,
// refined by golden-section steps on the two sample intervals around it; and dist2 there.
struct Nearest {
  double t = 0.0, d2 = std::numeric_limits<double>::infinity();
};
Nearest nearestOnCurve(const std::function<double(double)>& dist2, const PatchParamsOptions& o) {
  const int n = std::max(2, o.samplesPerCurve);
  int kBest = 0;
  double dBest = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= n; ++k) {
    const double d = dist2(double(k) / n);
    if (d < dBest) dBest = d, kBest = k;
  }
  double a = std::max(0.0, double(kBest - 1) / n), b = std::min(1.0, double(kBest + 1) / n);
  const double g = 0.6180339887498949;
  double t1 = b - g * (b - a), t2 = a + g * (b - a), d1 = dist2(t1), d2 = dist2(t2);
  for (int i = 0; i < o.refineSteps; ++i) {
    if (d1 < d2) {
      b = t2, t2 = t1, d2 = d1;
      t1 = b - g * (b - a), d1 = dist2(t1);
    } else {
      a = t1, t1 = t2, d1 = d2;
      t2 = a + g * (b - a), d2 = dist2(t2);
    }
  }
  const double t = d1 < d2 ? t1 : t2, dt = dist2(t);
  return dt <= dBest ? Nearest{t, dt} : Nearest{double(kBest) / n, dBest};
}

// The point of the patch's contours closest to x in 3D, as (u, v).
Vec2 closestContourParam(const SurfacePatch& patch, const Vec3& x, const PatchParamsOptions& o) {
  std::vector<const Contour*> contours{&patch.domain.outer};
  for (const Contour& h : patch.domain.holes) contours.push_back(&h);
  const Surface& s = *patch.surface;
  const Box2 dom = s.domain();
  auto at = [&](const Curve& c, double t) -> Vec2 { return c.point(t).cwiseMax(dom.lo).cwiseMin(dom.hi); };
  double best = std::numeric_limits<double>::infinity();
  Vec2 bestUv = Vec2::Zero();
  for (const Contour* contour : contours)
    for (const CurveUse& use : contour->curves) {
      const Curve& c = *use.curve;
      const Nearest r = nearestOnCurve([&](double t) { return (s.point(at(c, t)) - x).squaredNorm(); }, o);
      if (r.d2 < best) best = r.d2, bestUv = at(c, r.t);
    }
  return bestUv;
}

// A seam: two curves of one patch shared with each other (a sphere band's u = 0 and
// u = 2 pi). A vertex on it has two parameter points; the merged mesh keeps one.
struct Seam {
  const Curve* a;
  const Curve* b;
  bool reversed;  // a.start meets b.end
};

std::vector<std::vector<Seam>> seamsOf(const SurfaceModel& model) {
  std::vector<std::vector<Seam>> seams(model.patches.size());
  for (const SharedCurve& sc : model.shared) {
    const Curve *a = surface_mesher::curveAt(model, sc.a), *b = surface_mesher::curveAt(model, sc.b);
    if (sc.a.patch == sc.b.patch && a && b) seams[size_t(sc.a.patch)].push_back({a, b, sc.reversed});
  }
  return seams;
}

// The corners of an element of a patch with seams that spans more than half the patch's
// domain across: some corner lies on a seam and carries the parameters of its other side.
// Each corner takes one of its parameter points (its own, and on each seam curve it lies
// on, the point of the other curve at the same 3D point): the choice that keeps the
// element's corners closest together.
// (scale: the mesh's 3D extent.)
void unwrapSeamCorners(const SurfacePatch& patch, const std::vector<Seam>& seams, const Mesh& mesh, double scale,
                       const int* ids, Vec2* uv, int n, const PatchParamsOptions& o) {
  const Surface& s = *patch.surface;
  const Box2 dom = s.domain();
  const Vec2 size = dom.hi - dom.lo;
  Vec2 lo = uv[0], hi = uv[0];
  for (int k = 1; k < n; ++k) lo = lo.cwiseMin(uv[k]), hi = hi.cwiseMax(uv[k]);
  if (!((hi - lo).x() > 0.5 * size.x() || (hi - lo).y() > 0.5 * size.y())) return;
  const double tol2 = std::pow(1e-6 * size.norm(), 2);
  const double pull2 = std::pow(1e-6 * scale, 2);
  auto at = [&](const Curve& c, double t) -> Vec2 { return c.point(t).cwiseMax(dom.lo).cwiseMin(dom.hi); };
  std::vector<std::vector<Vec2>> images(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    std::vector<Vec2>& c = images[size_t(k)];
    c.push_back(uv[k]);
    const Vec3& x = mesh.points[size_t(ids[k])];
    // Two rounds: a corner of the patch's domain on two seams (a torus) has four images.
    for (int round = 0; round < 2; ++round)
      for (size_t i = 0, m = c.size(); i < m; ++i)
        for (const Seam& seam : seams)
          for (const auto& ends : {std::make_pair(seam.a, seam.b), std::make_pair(seam.b, seam.a)}) {
            const Curve *from = ends.first, *to = ends.second;  // (lambdas cannot capture structured bindings in C++17)
            const Vec2 q = c[i];
            const Nearest on = nearestOnCurve([&](double t) { return (at(*from, t) - q).squaredNorm(); }, o);
            if (on.d2 > tol2) continue;
            // The point of the other curve at x in 3D. A seam curve can be closed in 3D (a
            // torus's): both its ends are at x there, and the one at the matching parameter
            // is taken (a tiny pull towards it decides the tie).
            const double mapped = seam.reversed ? 1.0 - on.t : on.t;
            const Vec2 image =
                at(*to, nearestOnCurve(
                            [&](double t) {
                              return (s.point(at(*to, t)) - x).squaredNorm() + pull2 * (t - mapped) * (t - mapped);
                            },
                            o)
                            .t);
            if (std::none_of(c.begin(), c.end(), [&](const Vec2& y) { return (y - image).squaredNorm() <= tol2; }))
              c.push_back(image);
          }
  }
  // The most compact choice (least sum of squared corner distances; the first found on a
  // tie): at most 4 images per corner, so at most 4^4 choices.
  std::vector<size_t> pick(size_t(n), 0), best(size_t(n), 0);
  double bestCost = std::numeric_limits<double>::infinity();
  for (;;) {
    double cost = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        cost += (images[size_t(i)][pick[size_t(i)]] - images[size_t(j)][pick[size_t(j)]]).squaredNorm();
    if (cost < bestCost) bestCost = cost, best = pick;
    int k = 0;
    while (k < n && ++pick[size_t(k)] == images[size_t(k)].size()) pick[size_t(k++)] = 0;
    if (k == n) break;
  }
  for (int k = 0; k < n; ++k) uv[k] = images[size_t(k)][best[size_t(k)]];
}

}  // namespace

std::vector<Vec2> patchCornerParams(const SurfaceModel& model, const Mesh& mesh, const PatchParamsOptions& options) {
  const std::vector<int> patches = elementPatches(model, mesh);
  const size_t nv = mesh.points.size();
  // The patch that placed each vertex: the first (lowest index) patch among its elements.
  std::vector<int> placedBy(nv, std::numeric_limits<int>::max());
  struct Corners {  // an element's corners, without a heap allocation per element
    int v[4];
    int n;
    const int* begin() const { return v; }
    const int* end() const { return v + n; }
  };
  auto corners = [&](size_t e) {
    if (e < mesh.triangles.size()) {
      const auto& t = mesh.triangles[e];
      return Corners{{t[0], t[1], t[2], 0}, 3};
    }
    const auto& q = mesh.quads[e - mesh.triangles.size()];
    return Corners{{q[0], q[1], q[2], q[3]}, 4};
  };
  for (size_t e = 0; e < patches.size(); ++e)
    if (patches[e] >= 0)
      for (int v : corners(e)) placedBy[size_t(v)] = std::min(placedBy[size_t(v)], patches[e]);
  const std::vector<std::vector<Seam>> seams = seamsOf(model);
  std::vector<Vec2> out;
  out.reserve(3 * mesh.triangles.size() + 4 * mesh.quads.size());
  std::map<std::pair<int, int>, Vec2> found;  // (patch, vertex) -> (u, v) on that patch's contour
  for (size_t e = 0; e < patches.size(); ++e)
    for (int v : corners(e)) {
      const int p = patches[e];
      const Vec2 uv = mesh.params.size() == nv ? mesh.params[size_t(v)] : Vec2(mesh.points[size_t(v)].head<2>());
      if (p < 0 || placedBy[size_t(v)] == p) {
        out.push_back(uv);
        continue;
      }
      const auto key = std::make_pair(p, v);
      auto it = found.find(key);
      if (it == found.end())
        it = found.emplace(key, closestContourParam(model.patches[size_t(p)], mesh.points[size_t(v)], options)).first;
      out.push_back(it->second);
    }
  // Elements across a seam: their corners on the seam take the parameters of their side.
  const bool anySeam = std::any_of(seams.begin(), seams.end(), [](const auto& s) { return !s.empty(); });
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  for (size_t v = 0; anySeam && v < nv; ++v) {
    lo = v == 0 ? mesh.points[v] : Vec3(lo.cwiseMin(mesh.points[v]));
    hi = v == 0 ? mesh.points[v] : Vec3(hi.cwiseMax(mesh.points[v]));
  }
  const double scale = (hi - lo).norm() > 0.0 ? (hi - lo).norm() : 1.0;
  for (size_t e = 0, base = 0; anySeam && e < patches.size(); ++e) {
    const Corners c = corners(e);
    const int p = patches[e];
    if (p >= 0 && !seams[size_t(p)].empty())
      unwrapSeamCorners(model.patches[size_t(p)], seams[size_t(p)], mesh, scale, c.v, &out[base], c.n, options);
    base += size_t(c.n);
  }
  return out;
}

}  // namespace anisomesh

#include "anisomesh/surface/patch_params.h"

#include <algorithm>
#include <limits>
#include <map>

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

// The point of the patch's contours closest to x in 3D, as (u, v).
Vec2 closestContourParam(const SurfacePatch& patch, const Vec3& x, const PatchParamsOptions& o) {
  std::vector<const Contour*> contours{&patch.domain.outer};
  for (const Contour& h : patch.domain.holes) contours.push_back(&h);
  const Surface& s = *patch.surface;
  const Box2 dom = s.domain();
  auto at = [&](const Curve& c, double t) -> Vec2 { return c.point(t).cwiseMax(dom.lo).cwiseMin(dom.hi); };
  auto dist2 = [&](const Curve& c, double t) { return (s.point(at(c, t)) - x).squaredNorm(); };
  double best = std::numeric_limits<double>::infinity();
  Vec2 bestUv = Vec2::Zero();
  const int n = std::max(2, o.samplesPerCurve);
  for (const Contour* contour : contours)
    for (const CurveUse& use : contour->curves) {
      const Curve& c = *use.curve;
      int kBest = 0;
      double dBest = std::numeric_limits<double>::infinity();
      for (int k = 0; k <= n; ++k) {
        const double d = dist2(c, double(k) / n);
        if (d < dBest) dBest = d, kBest = k;
      }
      // Golden-section search on the two sample intervals around the best sample.
      double a = std::max(0.0, double(kBest - 1) / n), b = std::min(1.0, double(kBest + 1) / n);
      const double g = 0.6180339887498949;
      double t1 = b - g * (b - a), t2 = a + g * (b - a), d1 = dist2(c, t1), d2 = dist2(c, t2);
      for (int i = 0; i < o.refineSteps; ++i) {
        if (d1 < d2) {
          b = t2, t2 = t1, d2 = d1;
          t1 = b - g * (b - a), d1 = dist2(c, t1);
        } else {
          a = t1, t1 = t2, d1 = d2;
          t2 = a + g * (b - a), d2 = dist2(c, t2);
        }
      }
      const double t = d1 < d2 ? t1 : t2;
      const double d = std::min({dist2(c, t), dBest});
      if (d < best) {
        best = d;
        bestUv = dist2(c, t) <= dBest ? at(c, t) : at(c, double(kBest) / n);
      }
    }
  return bestUv;
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
  return out;
}

}  // namespace anisomesh

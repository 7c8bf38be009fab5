// Planar mesher: the seams of a decomposed domain polished after the merge. A cut's vertices
// are boundary vertices of both parts it separates, so neither part could move them nor swap
// the cut's edges; their triangles are the worst of a decomposed mesh (front 1e6: 29 of the
// 44 triangles below 0.8 touch a cut, min Q 0.70 against 0.78 elsewhere). Here the triangles
// around the cut vertices get the swaps and polish rounds of the adaptation loop's end.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

void Mesher::polishSeam(Mesh& merged, int seamBegin, int seamEnd) {
  const int nt = static_cast<int>(merged.triangles.size());
  auto onSeam = [&](int v) { return v >= seamBegin && v < seamEnd; };
  // The strip: every triangle with a cut vertex (a cut vertex's whole ball), in mesh order.
  std::vector<int> strip, local(merged.points.size(), -1), global;
  for (int t = 0; t < nt; ++t) {
    const auto& tv = merged.triangles[size_t(t)];
    if (!onSeam(tv[0]) && !onSeam(tv[1]) && !onSeam(tv[2])) continue;
    strip.push_back(t);
    for (const int v : tv)
      if (local[size_t(v)] < 0) {
        local[size_t(v)] = static_cast<int>(global.size());
        global.push_back(v);
      }
  }
  if (strip.empty()) return;
  const int nv = static_cast<int>(global.size());
  vx_.resize(size_t(nv));
  vbnd_.assign(size_t(nv), 0);
  vtri_.assign(size_t(nv), -1);
  vhint_.assign(size_t(nv), -1);
  for (int v = 0; v < nv; ++v) {
    const Vec2 p = merged.params[size_t(global[size_t(v)])];
    vx_[size_t(v)] = {p, queryMetric(p)};
    vhint_[size_t(v)] = queryHint_;
    vbnd_[size_t(v)] = global[size_t(v)] < seamBegin ? 1 : 0;  // the domain's boundary stays
  }
  // Triangles and their neighbours inside the strip (edges to the rest of the mesh, and the
  // domain's boundary, have none: nothing is swapped across them and balls there are open).
  const int ns = static_cast<int>(strip.size());
  tri_.assign(size_t(ns), Tri{{-1, -1, -1}, {-1, -1, -1}, 0, 0, 0});
  struct HalfEdge {
    int a, b, t, i;
  };
  std::vector<HalfEdge> half;
  half.reserve(3 * size_t(ns));
  for (int s = 0; s < ns; ++s) {
    const auto& tv = merged.triangles[size_t(strip[size_t(s)])];
    for (int i = 0; i < 3; ++i) tri_[size_t(s)].v[size_t(i)] = local[size_t(tv[size_t(i)])];
    for (int i = 0; i < 3; ++i) {
      const int a = tri_[size_t(s)].v[size_t(next3(i))], b = tri_[size_t(s)].v[size_t(prev3(i))];
      half.push_back({std::min(a, b), std::max(a, b), s, i});
      vtri_[size_t(tri_[size_t(s)].v[size_t(i)])] = s;
    }
  }
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.t < y.t);
  });
  for (size_t k = 0; k + 1 < half.size(); ++k)
    if (half[k].a == half[k + 1].a && half[k].b == half[k + 1].b) {
      tri_[size_t(half[k].t)].n[size_t(half[k].i)] = half[k + 1].t;
      tri_[size_t(half[k + 1].t)].n[size_t(half[k + 1].i)] = half[k].t;
      ++k;
    }
  stamp_.assign(size_t(ns), 0);
  vdirty_.assign(size_t(nv), 1);
  tq_.resize(size_t(ns));
  std::vector<int> work(static_cast<size_t>(ns)), next, scratch;
  for (int s = 0; s < ns; ++s) {
    tq_[size_t(s)] = triQuality(tri_[size_t(s)].v[0], tri_[size_t(s)].v[1], tri_[size_t(s)].v[2]);
    work[size_t(s)] = s;
  }
  // Swap sweeps until none is left, as the adaptation loop's (improvement.cpp).
  auto swaps = [&] {
    for (int k = 0; k < kMaxSwapSweeps && !work.empty(); ++k) {
      next.clear();
      swapSweep(work, next);
      ++epoch_;
      scratch.clear();
      for (const int t : next)
        if (tri_[size_t(t)].mark != epoch_) {
          tri_[size_t(t)].mark = epoch_;
          scratch.push_back(t);
        }
      work.swap(scratch);
    }
  };
  swaps();
  for (int round = 0; round < kPolishRounds; ++round) {
    work.clear();
    if (polishPass(work) == 0) break;
    swaps();
  }
  // Back into the merged mesh: moved vertices, and the strip's triangles slot for slot
  // (swaps keep the triangle count).
  for (int v = 0; v < nv; ++v) {
    const size_t g = size_t(global[size_t(v)]);
    merged.params[g] = vx_[size_t(v)].p;
    merged.points[g] = Vec3(vx_[size_t(v)].p.x(), vx_[size_t(v)].p.y(), 0.0);
  }
  for (int s = 0; s < ns; ++s)
    for (int i = 0; i < 3; ++i)
      merged.triangles[size_t(strip[size_t(s)])][size_t(i)] = global[size_t(tri_[size_t(s)].v[size_t(i)])];
}

}  // namespace planar

void polishDecompositionSeams(Mesh& merged, int seamBegin, int seamEnd, const ControlSpace& cs,
                              const PlanarMesherOptions& options) {
  if (options.improvementPasses <= 0 || seamEnd <= seamBegin) return;
  static const std::vector<BoundaryLoop> kNoLoops;
  PlanarMesherOptions o = options;
  o.progress = nullptr;
  o.timings = nullptr;
  planar::Mesher(kNoLoops, cs, o).polishSeam(merged, seamBegin, seamEnd);
}

}  // namespace anisomesh

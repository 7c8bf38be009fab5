// Planar mesher: the Delaunay kernel (point location, cavity fan, edge flip; the
// cavity search buildCavity is a template in mesher_impl.h).
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

// Visibility walk with a deterministic pseudo-random edge order (terminates on any
// triangulation with probability one). Returns -1 when leaving the domain.
int Mesher::locate(const Vec2& x, int t, bool stopAtConstraints) {
  const int limit = 4 * static_cast<int>(tri_.size()) + 100;
  for (int steps = 0; steps < limit; ++steps) {
    rng_ = rng_ * 1664525u + 1013904223u;
    const int r = static_cast<int>((rng_ >> 16) % 3u);
    bool moved = false;
    for (int k = 0; k < 3; ++k) {
      const int i = (r + k) % 3;
      const auto& v = tri_[t].v;
      if (orient(vx_[v[next3(i)]].p, vx_[v[prev3(i)]].p, x) < 0.0) {
        if (stopAtConstraints && cons(t, i)) return -1;
        const int nb = tri_[t].n[i];
        if (nb < 0) return -1;
        t = nb;
        moved = true;
        break;
      }
    }
    if (!moved) return t;
  }
  return -1;
}

int Mesher::commitCavity(int v) {
  // Small cavities link their new triangles by a scan of the boundary list (no random
  // access into per-vertex arrays); large ones through startAt_/endAt_.
  const bool small = bnd_.size() <= 24;
  if (!small && static_cast<int>(startAt_.size()) < static_cast<int>(vx_.size())) {
    startAt_.resize(vx_.size() + 1024, -1);
    endAt_.resize(vx_.size() + 1024, -1);
  }
  newTris_.clear();
  size_t reuse = 0;
  for (size_t k = 0; k < bnd_.size(); ++k) {
    int t;
    if (reuse < cav_.size()) {
      t = cav_[reuse++];
      ++stamp_[t];
    } else {
      t = allocTri();
    }
    newTris_.push_back(t);
  }
  for (; reuse < cav_.size(); ++reuse) {  // cannot happen for a disc cavity, kept for safety
    tri_[cav_[reuse]].v = {-1, -1, -1};
    freeTris_.push_back(cav_[reuse]);
  }
  for (size_t k = 0; k < bnd_.size(); ++k) {
    const auto& e = bnd_[k];
    const int t = newTris_[k];
    tri_[t].v = {e.a, e.b, v};
    tri_[t].n[2] = e.outer;
    tri_[t].c = e.c ? 4 : 0;
    tri_[t].acc = 0;
    if (e.outer >= 0) setNbrAcross(e.outer, e.a, e.b, t);
    if (!small) {
      startAt_[e.a] = t;
      endAt_[e.b] = t;
    }
  }
  const size_t nb = bnd_.size();
  if (small) {
    // The cavity boundary is a simple cycle: each of its vertices starts one edge. A table
    // from start vertex to edge (64 slots, open addressing, tagged per cavity) finds each
    // edge's successor: edge (b, v) borders the new triangle starting at b.
    auto slotOf = [](int vtx) { return static_cast<int>((static_cast<std::uint32_t>(vtx) * 2654435761u) >> 26); };
    const std::uint32_t tag = ++linkTag_;
    for (size_t k = 0; k < nb; ++k) {
      int s = slotOf(bnd_[k].a);
      while (link_[s].tag == tag) s = (s + 1) & 63;
      link_[s] = {tag, bnd_[k].a, static_cast<int>(k)};
    }
    for (size_t k = 0; k < nb; ++k) {
      const int t = newTris_[k], b = bnd_[k].b;
      int s = slotOf(b);
      while (link_[s].tag == tag && link_[s].v != b) s = (s + 1) & 63;
      if (link_[s].tag == tag) {
        const int succ = newTris_[link_[s].k];
        tri_[t].n[0] = succ;
        tri_[succ].n[1] = t;
      }
    }
    for (size_t k = 0; k < nb; ++k) vtri_[bnd_[k].a] = newTris_[k];
  } else {
    for (size_t k = 0; k < nb; ++k) {
      const int t = newTris_[k];
      tri_[t].n[0] = startAt_[bnd_[k].b];
      tri_[t].n[1] = endAt_[bnd_[k].a];
      vtri_[bnd_[k].a] = t;
    }
  }
  vtri_[v] = newTris_[0];
  return newTris_[0];
}

void Mesher::flip(int t, int i) {
  const int nb = tri_[t].n[i];
  const int p = tri_[t].v[i], u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
  int j = 0;
  while (tri_[nb].v[j] == u || tri_[nb].v[j] == w) ++j;
  const int q = tri_[nb].v[j];
  // t = (p, u, w), nb = (q, w, u)  ->  t = (p, u, q), nb = (q, w, p)
  const int nWP = tri_[t].n[next3(i)], nPU = tri_[t].n[prev3(i)];
  const bool cWP = cons(t, next3(i)), cPU = cons(t, prev3(i));
  // in nb = (q, w, u) at positions j, j+1, j+2: opposite w is edge (u, q), opposite u is (q, w)
  const int nUQ = tri_[nb].n[next3(j)], nQW = tri_[nb].n[prev3(j)];
  const bool cUQ = cons(nb, next3(j)), cQW = cons(nb, prev3(j));
  tri_[t].v = {p, u, q};
  tri_[t].n = {nUQ, nb, nPU};
  tri_[t].c = static_cast<std::uint8_t>((cUQ ? 1 : 0) | (cPU ? 4 : 0));
  tri_[nb].v = {q, w, p};
  tri_[nb].n = {nWP, t, nQW};
  tri_[nb].c = static_cast<std::uint8_t>((cWP ? 1 : 0) | (cQW ? 4 : 0));
  if (nUQ >= 0) setNbrAcross(nUQ, u, q, t);
  if (nWP >= 0) setNbrAcross(nWP, w, p, nb);
  ++stamp_[t];
  ++stamp_[nb];
  vtri_[p] = t;
  if (!vdirty_.empty()) vdirty_[p] = vdirty_[u] = vdirty_[q] = vdirty_[w] = 1;
  vtri_[u] = t;
  vtri_[q] = nb;
  vtri_[w] = nb;
}

}  // namespace planar
}  // namespace anisomesh

// Planar mesher: vertex renumbering along a Hilbert curve (cache locality).
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

namespace {

// Hilbert index of (x, y) in [0, 2^16)^2 (for cache-friendly renumbering).
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t n = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1u : 0u, ry = (y & s) ? 1u : 0u;
    d += static_cast<std::uint64_t>(s) * s * ((3u * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

}  // namespace

// Renumbers the inner vertices along a Hilbert curve and the triangles by their first
// vertex, dropping free slots: the frontal insertion creates them in order of size, not
// of position, and the later passes walk around vertices (cache misses dominate otherwise).
void Mesher::renumberSpatially() {
  // The insertion's per-triangle state is not needed any more: freed before the copies
  // below (the stage's memory peak), reallocated for the live triangles at the end.
  cache_.clear();
  cache_.shrink_to_fit();
  std::vector<std::uint32_t>().swap(forbid_);
  std::vector<std::uint32_t>().swap(stamp_);
  std::vector<std::uint32_t>().swap(queued_);
  const int nv = static_cast<int>(vx_.size());
  const int first = kSuper + nBoundary_;
  Vec2 lo = vx_[kSuper].p, hi = lo;
  for (int v = kSuper; v < nv; ++v) {
    lo = lo.cwiseMin(vx_[v].p);
    hi = hi.cwiseMax(vx_[v].p);
  }
  const Vec2 ext = (hi - lo).cwiseMax(Vec2(1e-300, 1e-300));
  // Hilbert keys (< 2^32) sorted by a stable two-digit radix sort: ties keep the vertex order.
  const int n = nv - first;
  std::vector<std::uint32_t> key(n);
  for (int v = first; v < nv; ++v) {
    const Vec2 f = (vx_[v].p - lo).cwiseQuotient(ext) * 65535.0;
    key[v - first] =
        static_cast<std::uint32_t>(hilbertIndex(static_cast<std::uint32_t>(f.x()), static_cast<std::uint32_t>(f.y())));
  }
  std::vector<int> order(n), tmp(n);
  for (int k = 0; k < n; ++k) tmp[k] = k;
  for (int shift = 0; shift < 32; shift += 16) {
    std::vector<int> cnt((1 << 16) + 1, 0);
    for (int k = 0; k < n; ++k) ++cnt[((key[tmp[k]] >> shift) & 0xffffu) + 1];
    for (int d = 0; d < (1 << 16); ++d) cnt[d + 1] += cnt[d];
    for (int k = 0; k < n; ++k) order[cnt[(key[tmp[k]] >> shift) & 0xffffu]++] = tmp[k];
    order.swap(tmp);
  }
  std::vector<int> vmap(nv);
  for (int v = 0; v < first; ++v) vmap[v] = v;
  for (int k = 0; k < n; ++k) vmap[first + tmp[k]] = first + k;
  {
    std::vector<Vtx> x(nv);
    std::vector<std::uint8_t> b(nv);
    for (int v = 0; v < nv; ++v) {
      x[vmap[v]] = vx_[v];
      b[vmap[v]] = vbnd_[v];
    }
    vx_.swap(x);
    vbnd_.swap(b);
  }
  // Triangles: counting sort by their smallest new vertex index (stable, linear).
  const int nt = static_cast<int>(tri_.size());
  std::vector<int> count(nv + 1, 0);
  for (int t = 0; t < nt; ++t) {
    if (tri_[t].v[0] < 0) continue;
    for (int i = 0; i < 3; ++i) tri_[t].v[i] = vmap[tri_[t].v[i]];
    ++count[std::min({tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]}) + 1];
  }
  for (int v = 0; v < nv; ++v) count[v + 1] += count[v];
  const int live = count[nv];
  std::vector<int> tmap(nt, -1);
  for (int t = 0; t < nt; ++t)
    if (tri_[t].v[0] >= 0) tmap[t] = count[std::min({tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]})]++;
  std::vector<Tri> tris(live);
  for (int t = 0; t < nt; ++t) {
    const int k = tmap[t];
    if (k < 0) continue;
    tris[k] = tri_[t];
    tris[k].acc = 0;
    tris[k].mark = 0;
    for (int i = 0; i < 3; ++i) tris[k].n[i] = tri_[t].n[i] >= 0 ? tmap[tri_[t].n[i]] : -1;
  }
  tri_.swap(tris);
  std::vector<Tri>().swap(tris);
  std::vector<int>().swap(tmap);
  freeTris_.clear();
  forbid_.assign(live, 0);
  stamp_.assign(live, 0);
  queued_.assign(live, 0);
  vtri_.assign(nv, -1);
  for (int t = 0; t < live; ++t)
    for (int i = 0; i < 3; ++i) vtri_[tri_[t].v[i]] = t;
}

}  // namespace planar
}  // namespace anisomesh

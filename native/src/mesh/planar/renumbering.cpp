// Planar mesher: vertex renumbering along a Hilbert curve (cache locality).
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

namespace {

// Spreads the 16 low bits of x to the even bit positions.
std::uint32_t interleaveBits(std::uint32_t x) {
  x = (x | (x << 8)) & 0x00FF00FFu;
  x = (x | (x << 4)) & 0x0F0F0F0Fu;
  x = (x | (x << 2)) & 0x33333333u;
  return (x | (x << 1)) & 0x55555555u;
}

// Hilbert index of (x, y) in [0, 2^16)^2 (for cache-friendly renumbering): the curve of the
// classic quadrant-rotation loop (16 steps, branches), computed bit-parallel as a prefix
// scan of the quadrant transforms (the same index for all 2^32 inputs, checked exhaustively).
std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
  std::uint32_t A, B, C, D;
  {
    const std::uint32_t a = x ^ y, b = 0xFFFFu ^ a, c = 0xFFFFu ^ (x | y), d = x & (y ^ 0xFFFFu);
    A = a | (b >> 1);
    B = (a >> 1) ^ a;
    C = ((c >> 1) ^ (b & (d >> 1))) ^ c;
    D = ((a & (c >> 1)) ^ (d >> 1)) ^ d;
  }
  for (int s = 2; s <= 8; s *= 2) {
    const std::uint32_t a = A, b = B, c = C, d = D;
    A = (a & (a >> s)) ^ (b & (b >> s));
    B = (a & (b >> s)) ^ (b & ((a ^ b) >> s));
    C ^= (a & (c >> s)) ^ (b & (d >> s));
    D ^= (b & (c >> s)) ^ ((a ^ b) & (d >> s));
  }
  const std::uint32_t a = C ^ (C >> 1), b = D ^ (D >> 1);
  const std::uint32_t i0 = x ^ y, i1 = b | (0xFFFFu ^ (i0 | a));
  return (interleaveBits(i1) << 1) | interleaveBits(i0);
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
  // Hilbert keys (< 2^32) sorted by a stable radix sort, three 11-bit digits (a part has
  // ~10^4 vertices: 2^16-bucket digits cost more in their prefix sums): ties keep the vertex order.
  const int n = nv - first;
  std::vector<std::uint32_t> key(n);
  for (int v = first; v < nv; ++v) {
    const Vec2 f = (vx_[v].p - lo).cwiseQuotient(ext) * 65535.0;
    key[v - first] = hilbertIndex(static_cast<std::uint32_t>(f.x()), static_cast<std::uint32_t>(f.y()));
  }
  std::vector<int> order(n), tmp(n);
  for (int k = 0; k < n; ++k) tmp[k] = k;
  constexpr int kDigit = 11;
  constexpr std::uint32_t kMask = (1u << kDigit) - 1;
  std::vector<int> cnt((1 << kDigit) + 1);
  for (int shift = 0; shift < 32; shift += kDigit) {
    std::fill(cnt.begin(), cnt.end(), 0);
    for (int k = 0; k < n; ++k) ++cnt[((key[tmp[k]] >> shift) & kMask) + 1];
    for (int d = 0; d < (1 << kDigit); ++d) cnt[d + 1] += cnt[d];
    for (int k = 0; k < n; ++k) order[cnt[(key[tmp[k]] >> shift) & kMask]++] = tmp[k];
    order.swap(tmp);
  }
  std::vector<int> vmap(nv);
  for (int v = 0; v < first; ++v) vmap[v] = v;
  for (int k = 0; k < n; ++k) vmap[first + tmp[k]] = first + k;
  {
    std::vector<Vtx> x;
    std::vector<std::uint8_t> b;
    x.reserve(nv + nv / 8 + 64);  // room for the improvement's splits, as for the triangles
    x.resize(nv);
    b.reserve(x.capacity());
    b.resize(nv);
    std::vector<int> h;
    h.reserve(x.capacity());
    h.resize(nv);
    for (int v = 0; v < nv; ++v) {
      x[vmap[v]] = vx_[v];
      b[vmap[v]] = vbnd_[v];
      h[vmap[v]] = vhint_[v];
    }
    vx_.swap(x);
    vbnd_.swap(b);
    vhint_.swap(h);
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
  std::vector<Tri> tris;
  // Room for the splits of the improvement (a few %): no reallocation copying every triangle.
  tris.reserve(live + live / 8 + 64);
  tris.resize(live);
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
  stamp_.reserve(tri_.capacity());
  stamp_.assign(live, 0);
  improving_ = true;  // forbid_, queued_ and cache_ stay empty from here on
  vtri_.reserve(vx_.capacity());
  vtri_.assign(nv, -1);
  for (int t = 0; t < live; ++t)
    for (int i = 0; i < 3; ++i) vtri_[tri_[t].v[i]] = t;
}

}  // namespace planar
}  // namespace anisomesh

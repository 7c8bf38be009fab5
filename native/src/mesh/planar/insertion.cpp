// Planar mesher: frontal-Delaunay insertion of the inner nodes in the metric.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

void Mesher::computeCache(int t) {
  const auto& v = tri_[t].v;
  TriCache& c = cache_[t];
  c.m = SymMt::average3(vx_[v[0]].m, vx_[v[1]].m, vx_[v[2]].m);
  const Vec2& pa = vx_[v[0]].p;
  const Vec2 b = c.m.apply(vx_[v[1]].p - pa), cc = c.m.apply(vx_[v[2]].p - pa);
  const double d = 2.0 * (b.x() * cc.y() - b.y() * cc.x());
  if (!(d > 0.0)) {  // degenerate in floating point: never refine it, never absorb points
    c.r2 = 0.0;
    c.cx = pa.x();
    c.cy = pa.y();
    return;
  }
  const double b2 = b.squaredNorm(), c2 = cc.squaredNorm();
  const double inv = 1.0 / d;  // two divisions instead of four (this runs once per new triangle)
  const double ux = (cc.y() * b2 - b.y() * c2) * inv, uy = (b.x() * c2 - cc.x() * b2) * inv;
  c.r2 = ux * ux + uy * uy;
  const double idet = 1.0 / c.m.det();  // centre = pa + Mt^-1 u
  c.cx = pa.x() + (c.m.c * ux - c.m.b * uy) * idet;
  c.cy = pa.y() + (c.m.a * uy - c.m.b * ux) * idet;
}

void Mesher::insertInnerNodes() {
  // Bucket queue on the metric radius (4 buckets per doubling of r^2), last in first out
  // within a bucket: the largest triangles go first as in Rebay's method, while the LIFO
  // order keeps consecutive insertions close together (cache locality).
  struct Item {
    int t;
    std::uint32_t stamp;
  };
  std::vector<std::vector<Item>> buckets(2 * kBucketOffset);
  int top = -1;
  auto bucketOf = [](double r2) {
    // 4 e + floor((m - 0.5) 8) for r2 = m 2^e, m in [0.5, 1): for normal r2 that is the
    // biased exponent and the two leading fraction bits (what frexp would give, cheaper).
    std::uint64_t bits;
    std::memcpy(&bits, &r2, sizeof bits);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    int b;
    if (biased > 0 && biased < 0x7ff && !(bits >> 63)) {
      b = 4 * (biased - 1022) + static_cast<int>((bits >> 50) & 3u) + kBucketOffset;
    } else {
      int e;
      const double m = std::frexp(r2, &e);
      b = 4 * e + static_cast<int>((m - 0.5) * 8.0) + kBucketOffset;
    }
    return std::min(std::max(b, 0), 2 * kBucketOffset - 1);
  };
  const double acc2 = kAcceptRadius * kAcceptRadius;

  auto isActive = [&](int t) {
    if (tri_[t].acc) return false;
    for (int i = 0; i < 3; ++i) {
      const int nb = tri_[t].n[i];
      if (nb < 0 || cons(t, i) || tri_[nb].acc) return true;
    }
    return false;
  };
  auto pushIfActive = [&](int t) {
    if (queued_[t] != stamp_[t] && isActive(t)) {
      queued_[t] = stamp_[t];
      const int b = bucketOf(cache_[t].r2);
      buckets[b].push_back({t, stamp_[t]});
      top = std::max(top, b);
    }
  };
  const int nt0 = static_cast<int>(tri_.size());
  for (int t = 0; t < nt0; ++t) {
    computeCache(t);
    tri_[t].acc = cache_[t].r2 <= acc2;
  }
  for (int t = 0; t < nt0; ++t) pushIfActive(t);

  const double minDist2 = opt_.minNodeDistance * opt_.minNodeDistance;
  const double budget = static_cast<double>(opt_.maxElements);
  std::int64_t inserted = 0;
  for (;;) {
    while (top >= 0 && buckets[top].empty()) --top;
    if (top < 0) break;
    const Item it = buckets[top].back();
    buckets[top].pop_back();
    const int t = it.t;
    if (stamp_[t] != it.stamp || tri_[t].v[0] < 0 || tri_[t].acc) continue;
    queued_[t] = std::numeric_limits<std::uint32_t>::max();
    // Front edge: an edge on the boundary or next to an accepted triangle, the one
    // whose metric length is closest to 1.
    const TriCache& tc = cache_[t];
    int edge = -1;
    double bestDev = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
      const int nb = tri_[t].n[i];
      if (!(nb < 0 || cons(t, i) || tri_[nb].acc)) continue;
      const double len = tc.m.length(vx_[tri_[t].v[prev3(i)]].p - vx_[tri_[t].v[next3(i)]].p);
      const double dev = std::fabs(len - 1.0);
      if (dev < bestDev) {
        bestDev = dev;
        edge = i;
      }
    }
    if (edge < 0) continue;  // not on the front any more; re-queued when a neighbour is accepted
    const Vec2& pa = vx_[tri_[t].v[next3(edge)]].p;
    const Vec2& pb = vx_[tri_[t].v[prev3(edge)]].p;
    // Rebay's point placement in the triangle's metric space.
    const Vec2 mid = 0.5 * (pa + pb);
    const Vec2 e = tc.m.apply(pb - pa);
    const double elen = e.norm();
    const double p = 0.5 * elen;
    const Vec2 nrm(-e.y() / elen, e.x() / elen);  // towards the triangle's interior
    const double q = tc.m.apply(Vec2(tc.cx, tc.cy) - mid).dot(nrm);
    const double R = std::sqrt(tc.r2);
    const double rho = std::min(std::max(kIdealRadius, p), R);
    double d = rho + std::sqrt(std::max(0.0, rho * rho - p * p));
    d = std::min(d, 0.999 * (q + R));
    // A point is taken when it lies in the domain, its cavity is star-shaped, and no
    // cavity vertex is closer than minNodeDistance in the front triangle's metric.
    auto acceptable = [&](const Vec2& x) {
      if (!x.allFinite()) return false;
      const int t0 = locate(x, t, true);
      if (t0 < 0 || !(cache_[t0].r2 > 0.0)) return false;
      const bool star = buildCavity(x, t0, [&](int nb) {
        const TriCache& c = cache_[nb];
        return c.m.apply(x - Vec2(c.cx, c.cy)).squaredNorm() < c.r2;
      });
      if (!star) return false;
      for (const auto& be : bnd_)
        if (tc.m.apply(vx_[be.a].p - x).squaredNorm() < minDist2) return false;
      return true;
    };
    Vec2 x = mid + tc.m.solve(d * nrm);
    bool ok = d > 0.0 && acceptable(x);
    // Where the metric varies fast across a large triangle, Rebay's point (placed from one
    // front edge, judged in the triangle's averaged metric) can fall next to a vertex;
    // giving up there left pockets with edges up to 3x the unit length that the
    // improvement could not split. The metric circumcentre lies R > kRetryRadius from the
    // triangle's vertices.
    if (!ok && R > kRetryRadius) {
      x = Vec2(tc.cx, tc.cy);
      ok = acceptable(x);
    }
    if (!ok) {
      tri_[t].acc = 1;  // give up on this triangle; its neighbours join the front
      for (int i = 0; i < 3; ++i)
        if (tri_[t].n[i] >= 0) pushIfActive(tri_[t].n[i]);
      continue;
    }
    const int v = static_cast<int>(vx_.size());
    int hint = hintOf(tri_[t].v[next3(edge)]);  // x is about a unit length from the front edge
    vx_.push_back({x, queryMetric(x, hint)});
    vhint_.push_back(hint);
    vbnd_.push_back(0);
    vtri_.push_back(-1);
    commitCavity(v);
    for (const int nt : newTris_) {
      computeCache(nt);
      tri_[nt].acc = cache_[nt].r2 <= acc2;
    }
    for (const int nt : newTris_) {
      if (tri_[nt].acc) {
        // Only the outer neighbour can newly join the front: the other two neighbours
        // are new triangles, handled by this loop.
        if (tri_[nt].n[2] >= 0) pushIfActive(tri_[nt].n[2]);
      } else {
        pushIfActive(nt);
      }
    }
    if ((++inserted & 4095) == 0) {
      const double live = liveTriangles();
      if (live * elementRatio_ > budget) {
        std::ostringstream os;
        os << "meshPlanarBoundary: the mesh exceeds the element budget of " << opt_.maxElements
           << " elements during insertion (estimate was " << saturatedInt64(estimate_) << ")";
        throw Error(ErrorCode::ElementBudgetExceeded, os.str());
      }
      checkProgress(0.1 + 0.7 * std::min(1.0, live / std::max(1.0, estimate_)));
    }
  }
}

}  // namespace planar
}  // namespace anisomesh

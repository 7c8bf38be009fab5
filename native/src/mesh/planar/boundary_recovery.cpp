// Planar mesher: boundary-only triangulation, recovery of the boundary edges by flips,
// removal of the triangles outside the domain.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

void Mesher::triangulateBoundary() {
  // Vertices: 4 super-box corners, then the boundary points loop by loop in input order.
  Vec2 lo = loops_[0].points[0], hi = lo;
  int n = 0;
  for (const auto& lp : loops_)
    for (const auto& p : lp.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
      ++n;
    }
  const Vec2 c = 0.5 * (lo + hi);
  const double r = std::max(1e-300, 4.0 * std::max(hi.x() - lo.x(), hi.y() - lo.y()));
  vx_.reserve(n + kSuper);
  vx_.push_back({c + Vec2(-r, -r), SymMt()});
  vx_.push_back({c + Vec2(r, -r), SymMt()});
  vx_.push_back({c + Vec2(r, r), SymMt()});
  vx_.push_back({c + Vec2(-r, r), SymMt()});
  for (const auto& lp : loops_) {
    const int base = static_cast<int>(vx_.size());
    const int m = static_cast<int>(lp.points.size());
    for (int i = 0; i < m; ++i) {
      vx_.push_back({lp.points[i], SymMt()});
      bedges_.push_back({base + i, base + (i + 1) % m});
      bedgeRefs_.push_back(lp.edgeRefs[i]);
    }
  }
  nBoundary_ = n;
  vbnd_.assign(vx_.size(), 1);
  vtri_.assign(vx_.size(), -1);
  const int t0 = allocTri(), t1 = allocTri();
  tri_[t0].v = {0, 1, 2};
  tri_[t1].v = {0, 2, 3};
  tri_[t0].n = {-1, t1, -1};
  tri_[t1].n = {-1, -1, t0};
  vtri_[0] = vtri_[1] = vtri_[2] = t0;
  vtri_[3] = t1;

  int last = t0;
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v) {
    const Vec2 x = vx_[v].p;
    int t = locate(x, last, false);
    if (t < 0) {  // cannot happen inside the super-box; scan as a last resort
      for (int k = 0; k < static_cast<int>(tri_.size()) && t < 0; ++k)
        if (tri_[k].v[0] >= 0 && orient(vx_[tri_[k].v[0]].p, vx_[tri_[k].v[1]].p, x) >= 0 &&
            orient(vx_[tri_[k].v[1]].p, vx_[tri_[k].v[2]].p, x) >= 0 &&
            orient(vx_[tri_[k].v[2]].p, vx_[tri_[k].v[0]].p, x) >= 0)
          t = k;
      require(t >= 0, ErrorCode::Internal, "meshPlanarBoundary: point location failed");
    }
    for (int k = 0; k < 3; ++k)
      if (vx_[tri_[t].v[k]].p == x) {
        std::ostringstream os;
        os << "meshPlanarBoundary: duplicate boundary point (" << x.x() << ", " << x.y() << ")";
        throw Error(ErrorCode::InvalidArgument, os.str());
      }
    const bool ok = buildCavity(x, t, [&](int nb) {
      const auto& tv = tri_[nb].v;
      return incircle(vx_[tv[0]].p, vx_[tv[1]].p, vx_[tv[2]].p, x) > 0.0;
    });
    require(ok, ErrorCode::Internal, "meshPlanarBoundary: Delaunay cavity is not star-shaped");
    last = commitCavity(v);
  }

  for (size_t e = 0; e < bedges_.size(); ++e) recoverEdge(bedges_[e][0], bedges_[e][1]);
}

void Mesher::recoverEdge(int a, int b) {
  auto setConstrained = [&](int t, int i) {
    tri_[t].c |= static_cast<std::uint8_t>(1 << i);
    const int nb = tri_[t].n[i];
    const int u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
    for (int j = 0; j < 3; ++j)
      if (tri_[nb].v[next3(j)] == w && tri_[nb].v[prev3(j)] == u) tri_[nb].c |= static_cast<std::uint8_t>(1 << j);
  };
  auto onSegmentError = [&](int v) {
    std::ostringstream os;
    os << "meshPlanarBoundary: boundary point (" << vx_[v].p.x() << ", " << vx_[v].p.y()
       << ") lies on the boundary segment (" << vx_[a].p.x() << ", " << vx_[a].p.y() << ")-(" << vx_[b].p.x() << ", "
       << vx_[b].p.y() << ")";
    throw Error(ErrorCode::SelfIntersectingContour, os.str());
  };
  int idx;
  int t = findEdge(a, b, &idx);
  if (t >= 0) {
    setConstrained(t, idx);
    return;
  }
  const Vec2& pa = vx_[a].p;
  const Vec2& pb = vx_[b].p;
  // Find the triangle around a through which segment ab leaves a.
  std::deque<std::pair<int, int>> crossing;
  int cur = vtri_[a];
  int u = -1, w = -1;
  for (int guard = 0;; ++guard) {
    require(guard < 1000000, ErrorCode::Internal, "meshPlanarBoundary: boundary recovery: no start triangle");
    const auto& v = tri_[cur].v;
    const int i = v[0] == a ? 0 : (v[1] == a ? 1 : 2);
    const int x = v[next3(i)], y = v[prev3(i)];
    const double ox = orient(pa, pb, vx_[x].p), oy = orient(pa, pb, vx_[y].p);
    if (ox == 0.0 && (vx_[x].p - pa).dot(pb - pa) > 0.0) onSegmentError(x);
    if (ox < 0.0 && oy > 0.0) {
      u = x;
      w = y;
      break;
    }
    cur = tri_[cur].n[next3(i)];
  }
  // Walk along ab collecting the crossed edges.
  for (int guard = 0;; ++guard) {
    require(guard < 10000000, ErrorCode::Internal, "meshPlanarBoundary: boundary recovery walk failed");
    int i = 0;
    while (tri_[cur].v[i] == u || tri_[cur].v[i] == w) ++i;
    if (cons(cur, i)) {
      std::ostringstream os;
      os << "meshPlanarBoundary: boundary segment (" << pa.x() << ", " << pa.y() << ")-(" << pb.x() << ", " << pb.y()
         << ") crosses another boundary segment";
      throw Error(ErrorCode::SelfIntersectingContour, os.str());
    }
    crossing.emplace_back(u, w);
    const int nb = tri_[cur].n[i];
    int j = 0;
    while (tri_[nb].v[j] == u || tri_[nb].v[j] == w) ++j;
    const int z = tri_[nb].v[j];
    cur = nb;
    if (z == b) break;
    const double oz = orient(pa, pb, vx_[z].p);
    if (oz == 0.0) onSegmentError(z);
    if (oz < 0.0)
      u = z;
    else
      w = z;
  }
  // Flip crossing edges until none is left (terminates for a segment between two vertices).
  const std::int64_t cap = 1000 + 100 * static_cast<std::int64_t>(crossing.size()) * crossing.size();
  for (std::int64_t guard = 0; !crossing.empty(); ++guard) {
    require(guard < cap, ErrorCode::Internal, "meshPlanarBoundary: boundary recovery did not converge");
    const auto e = crossing.front();
    crossing.pop_front();
    int ti;
    const int tt = findEdge(e.first, e.second, &ti);
    require(tt >= 0, ErrorCode::Internal, "meshPlanarBoundary: boundary recovery lost an edge");
    const int nb = tri_[tt].n[ti];
    const int p = tri_[tt].v[ti];
    int j = 0;
    while (tri_[nb].v[j] == e.first || tri_[nb].v[j] == e.second) ++j;
    const int q = tri_[nb].v[j];
    // t = (p, u, w); flipping gives (p, u, q) and (q, w, p): both must be counter-clockwise.
    if (orient(vx_[p].p, vx_[e.first].p, vx_[q].p) <= 0.0 || orient(vx_[q].p, vx_[e.second].p, vx_[p].p) <= 0.0) {
      crossing.push_back(e);
      continue;
    }
    flip(tt, ti);
    if (p == a || p == b || q == a || q == b) continue;
    const double op = orient(pa, pb, vx_[p].p), oq = orient(pa, pb, vx_[q].p);
    if ((op < 0.0 && oq > 0.0) || (op > 0.0 && oq < 0.0)) crossing.emplace_back(p, q);
  }
  t = findEdge(a, b, &idx);
  require(t >= 0, ErrorCode::Internal, "meshPlanarBoundary: boundary edge could not be recovered");
  setConstrained(t, idx);
}

// Keeps the triangles separated from the super-box by an odd number of constrained
// edges (inside the outer loop, outside every hole), whatever the loops' orientation.
void Mesher::removeOutside() {
  const int nt = static_cast<int>(tri_.size());
  std::vector<int> depth(nt, -1);
  std::deque<int> dq;
  for (int t = 0; t < nt; ++t) {
    const auto& v = tri_[t].v;
    if (v[0] >= 0 && (v[0] < kSuper || v[1] < kSuper || v[2] < kSuper)) {
      depth[t] = 0;
      dq.push_back(t);
    }
  }
  while (!dq.empty()) {  // 0-1 BFS: crossing a constrained edge costs one
    const int t = dq.front();
    dq.pop_front();
    for (int i = 0; i < 3; ++i) {
      const int nb = tri_[t].n[i];
      if (nb < 0) continue;
      const int d = depth[t] + (cons(t, i) ? 1 : 0);
      if (depth[nb] < 0 || d < depth[nb]) {
        depth[nb] = d;
        if (cons(t, i))
          dq.push_back(nb);
        else
          dq.push_front(nb);
      }
    }
  }
  // The region inside the outer loop has depth 1 and each hole's inside depth 2; anything
  // else is a hole outside the outer loop, or a hole inside another hole.
  int firstEdge = 0;
  for (size_t l = 0; l < loops_.size(); ++l) {
    const int m = static_cast<int>(loops_[l].points.size());
    const int a = bedges_[firstEdge][0], b = bedges_[firstEdge][1];
    int idx;
    const int t = findEdge(a, b, &idx);
    require(t >= 0, ErrorCode::Internal, "meshPlanarBoundary: boundary edge lost");
    const int nb = tri_[t].n[idx];
    const int deeper = std::max(depth[t], nb >= 0 ? depth[nb] : 0);
    if (l == 0) {
      require(deeper == 1, ErrorCode::HoleOutsideDomain,
              "meshPlanarBoundary: the outer loop (loop 0) lies inside another loop");
    } else {
      require(deeper == 2, ErrorCode::HoleOutsideDomain,
              "meshPlanarBoundary: hole loop " + std::to_string(l) +
                  (deeper < 2 ? " lies outside the outer loop" : " lies inside another hole"));
    }
    firstEdge += m;
  }
  std::vector<int> remap(nt, -1);
  int kept = 0;
  for (int t = 0; t < nt; ++t)
    if (tri_[t].v[0] >= 0 && depth[t] >= 0 && (depth[t] & 1)) remap[t] = kept++;
  require(kept > 0, ErrorCode::InvalidDomain, "meshPlanarBoundary: the boundary loops enclose no area");
  std::vector<Tri> tris(kept);
  for (int t = 0; t < nt; ++t) {
    const int k = remap[t];
    if (k < 0) continue;
    tris[k] = tri_[t];
    tris[k].acc = 0;
    tris[k].mark = 0;
    for (int i = 0; i < 3; ++i) tris[k].n[i] = tri_[t].n[i] >= 0 ? remap[tri_[t].n[i]] : -1;
  }
  tri_.swap(tris);
  freeTris_.clear();
  forbid_.assign(kept, 0);
  stamp_.assign(kept, 0);
  queued_.assign(kept, std::numeric_limits<std::uint32_t>::max());
  cache_.assign(kept, TriCache());
  std::fill(vtri_.begin(), vtri_.end(), -1);
  for (int t = 0; t < kept; ++t)
    for (int i = 0; i < 3; ++i) vtri_[tri_[t].v[i]] = t;
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v)
    require(vtri_[v] >= 0, ErrorCode::HoleOutsideDomain,
            "meshPlanarBoundary: a boundary point is not on the meshed region (hole outside the outer loop?)");
}

}  // namespace planar
}  // namespace anisomesh

// Planar mesher: collapse of short edges and split of long inner edges.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

// Collapses inner vertex a onto its neighbour b (edge a-b too short), b staying or, with
// toMidpoint (b inner too), moving to the edge's midpoint: the two triangles of the edge
// disappear, the rest of a's ball is re-attached to b. Refused when the link condition
// fails (would create a duplicate edge), when a triangle would turn or become poor, or
// when a new edge would be too long.
bool Mesher::tryCollapse(int a, int b, bool toMidpoint, std::vector<int>& touched) {
  if (vbnd_[a]) return false;
  std::vector<int>& ball = colBall_;
  std::vector<int>& ring = colRing_;
  if (!closedBall(a, ball, ring)) return false;
  const int deg = static_cast<int>(ring.size());
  if (deg < 4) return false;
  int kb = -1;
  for (int k = 0; k < deg; ++k)
    if (ring[k] == b) kb = k;
  if (kb < 0) return false;
  const int k1 = kb, k2 = (kb + deg - 1) % deg;  // T1 = (a, b, x), T2 = (a, y, b)
  const int x = ring[(kb + 1) % deg], y = ring[k2];
  // Link condition: the only common neighbours of a and b are x and y.
  ++epoch_;
  if (vmark_.size() < vx_.size()) vmark_.resize(vx_.size() + 1024, 0);
  for (const int r : ring) vmark_[r] = epoch_;
  {
    int tb = vtri_[b];
    for (int dir = 0; dir < 2; ++dir) {  // counter-clockwise, then clockwise if open
      int u = tb;
      for (int guard = 0; guard < 1000 && u >= 0; ++guard) {
        const auto& tv = tri_[u].v;
        const int i = tv[0] == b ? 0 : (tv[1] == b ? 1 : 2);
        for (const int w : {tv[next3(i)], tv[prev3(i)]})
          if (w != a && w != x && w != y && vmark_[w] == epoch_) return false;
        u = tri_[u].n[dir == 0 ? next3(i) : prev3(i)];
        if (u == tb) break;
      }
      if (u == tb) break;
    }
  }
  // Geometry: the re-attached triangles (and, when b moves, b's own) stay
  // counter-clockwise, fair, with no long edge.
  Vec2 pb = vx_[b].p;
  SymMt mb = vx_[b].m;
  int hint = hintOf(b);  // the queries below are next to b
  if (toMidpoint) {
    pb = 0.5 * (vx_[a].p + vx_[b].p);
    mb = queryMetric(pb, hint);
  }
  auto quality = [&](int r, int c) {
    return metricTriangleQuality(SymMt::average3(mb, vx_[r].m, vx_[c].m), pb, vx_[r].p, vx_[c].p);
  };
  auto tooLong = [&](int r) { return SymMt::average2(mb, vx_[r].m).length(vx_[r].p - pb) > colMaxLength_; };
  double before = std::numeric_limits<double>::infinity();
  for (const int bt : ball) before = std::min(before, tq_[bt]);
  std::vector<int>& ballB = colBallB_;
  ballB.clear();
  if (toMidpoint) {  // b is inner: its ball is closed
    const int s0 = vtri_[b];
    int u = s0;
    for (int guard = 0; guard < 1000; ++guard) {
      const auto& tv = tri_[u].v;
      const int i = tv[0] == b ? 0 : (tv[1] == b ? 1 : 2);
      if (tv[next3(i)] != a && tv[prev3(i)] != a) {
        ballB.push_back(u);
        before = std::min(before, tq_[u]);
      }
      u = tri_[u].n[next3(i)];
      if (u < 0 || u == s0) break;
    }
    if (u != s0) return false;
    if (colOptimal_) {
      // The mean over the merged ring (a's and b's) of the points at unit metric length
      // from each ring vertex towards the midpoint.
      const Vec2 pm = pb;
      Vec2 target(0.0, 0.0);
      int count = 0;
      auto add = [&](int r) {
        const Vec2 d = pm - vx_[r].p;
        const double len = SymMt::average2(mb, vx_[r].m).length(d);
        target += len > 0.0 ? Vec2(vx_[r].p + d / len) : pm;
        ++count;
      };
      for (const int r : ring)
        if (r != b) add(r);
      for (const int bt : ballB) {
        const auto& tv = tri_[bt].v;
        add(tv[next3(tv[0] == b ? 0 : (tv[1] == b ? 1 : 2))]);
      }
      pb = target / static_cast<double>(count);
      mb = queryMetric(pb, hint);
    }
    if (colSearch_) placeMergedVertex(ring, k1, k2, ballB, b, pb, mb);
  }
  const double floor = std::min(before, colMinQuality_);
  for (int k = 0; k < deg; ++k) {
    const int r = ring[k];
    if (r != b && tooLong(r)) return false;
    if (k == k1 || k == k2) continue;
    const int c = ring[(k + 1) % deg];
    if (orient(pb, vx_[r].p, vx_[c].p) <= 0.0) return false;
    if (!(quality(r, c) >= floor + colMinGain_)) return false;
  }
  for (const int u : ballB) {
    const auto& tv = tri_[u].v;
    const int i = tv[0] == b ? 0 : (tv[1] == b ? 1 : 2);
    const int r = tv[next3(i)], c = tv[prev3(i)];
    if (tooLong(r)) return false;
    if (orient(pb, vx_[r].p, vx_[c].p) <= 0.0) return false;
    if (!(quality(r, c) >= floor + colMinGain_)) return false;
  }
  // Apply.
  vx_[b].p = pb;
  vx_[b].m = mb;
  vhint_[b] = hint;
  const int T1 = ball[k1], T2 = ball[k2];
  auto relink = [&](int dead, int keep, int other, bool constrained) {
    // In keep, the entry pointing at dead now points at other (with dead's constraint bit).
    if (keep < 0) return;
    for (int j = 0; j < 3; ++j)
      if (tri_[keep].n[j] == dead) {
        tri_[keep].n[j] = other;
        if (constrained)
          tri_[keep].c |= static_cast<std::uint8_t>(1 << j);
        else
          tri_[keep].c &= static_cast<std::uint8_t>(~(1 << j));
        return;
      }
  };
  auto oppositeOf = [&](int tri, int v) {  // index of vertex v in tri
    const auto& tv = tri_[tri].v;
    return tv[0] == v ? 0 : (tv[1] == v ? 1 : 2);
  };
  const int i1a = oppositeOf(T1, a), i1b = oppositeOf(T1, b);
  const int n1b = tri_[T1].n[i1a], n1a = tri_[T1].n[i1b];  // across (b, x) and (x, a)
  const bool c1 = cons(T1, i1a);
  const int i2a = oppositeOf(T2, a), i2b = oppositeOf(T2, b);
  const int n2b = tri_[T2].n[i2a], n2a = tri_[T2].n[i2b];  // across (y, b) and (a, y)
  const bool c2 = cons(T2, i2a);
  relink(T1, n1a, n1b, c1);
  relink(T1, n1b, n1a, c1);
  relink(T2, n2a, n2b, c2);
  relink(T2, n2b, n2a, c2);
  for (int k = 0; k < deg; ++k) {
    if (k == k1 || k == k2) continue;
    const int bt = ball[k];
    tri_[bt].v[oppositeOf(bt, a)] = b;
    tq_[bt] = triQuality(tri_[bt].v[0], tri_[bt].v[1], tri_[bt].v[2]);
    touched.push_back(bt);
  }
  for (const int dead : {T1, T2}) {
    tri_[dead].v = {-1, -1, -1};
    ++stamp_[dead];
    freeTris_.push_back(dead);
  }
  if (toMidpoint) {
    for (const int u : ballB) {
      const auto& tv = tri_[u].v;
      tq_[u] = triQuality(tv[0], tv[1], tv[2]);
      touched.push_back(u);
      for (int i = 0; i < 3; ++i) vdirty_[tv[i]] = 1;
    }
  }
  for (const int r : ring) vdirty_[r] = 1;
  vtri_[b] = n1a;
  vtri_[x] = n1a;
  vtri_[y] = n2a;
  vtri_[a] = -1;
  vbnd_[a] = 2;
  return true;
}

// Splits the inner edge opposite vertex i of t at its midpoint: t = (p, u, w) and its
// neighbour (q, w, u) become four triangles around the new vertex. Refused when a new
// triangle would not be counter-clockwise or would be poor (below kSplitMinQuality and
// below the worse of the two triangles).
bool Mesher::trySplit(int t, int i, std::vector<int>& touched) {
  const int nb = tri_[t].n[i];
  const int p = tri_[t].v[i], u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
  int j = 0;
  while (tri_[nb].v[j] == u || tri_[nb].v[j] == w) ++j;
  const int q = tri_[nb].v[j];
  const Vec2 x = 0.5 * (vx_[u].p + vx_[w].p);
  if (orient(vx_[p].p, vx_[u].p, x) <= 0.0 || orient(vx_[p].p, x, vx_[w].p) <= 0.0 ||
      orient(vx_[q].p, vx_[w].p, x) <= 0.0 || orient(vx_[q].p, x, vx_[u].p) <= 0.0)
    return false;
  const int v = static_cast<int>(vx_.size());
  int hint = hintOf(u);
  vx_.push_back({x, queryMetric(x, hint)});
  const double floor = std::min(kSplitMinQuality, std::min(tq_[t], tq_[nb]));
  const double q1 = triQuality(p, u, v), q2 = triQuality(p, v, w), q3 = triQuality(q, w, v), q4 = triQuality(q, v, u);
  if (!(std::min({q1, q2, q3, q4}) >= floor)) {
    vx_.pop_back();
    return false;
  }
  vhint_.push_back(hint);
  vbnd_.push_back(0);
  vtri_.push_back(t);
  vdirty_.push_back(1);
  const int nWP = tri_[t].n[next3(i)], nPU = tri_[t].n[prev3(i)];
  const bool cWP = cons(t, next3(i)), cPU = cons(t, prev3(i));
  const int nUQ = tri_[nb].n[next3(j)], nQW = tri_[nb].n[prev3(j)];
  const bool cUQ = cons(nb, next3(j)), cQW = cons(nb, prev3(j));
  const int t2 = allocTri(), nb2 = allocTri();
  if (tq_.size() < tri_.size()) tq_.resize(tri_.size() + 1024, 0.0);
  tri_[t].v = {p, u, v};
  tri_[t].n = {nb2, t2, nPU};
  tri_[t].c = static_cast<std::uint8_t>(cPU ? 4 : 0);
  tri_[t2].v = {p, v, w};
  tri_[t2].n = {nb, nWP, t};
  tri_[t2].c = static_cast<std::uint8_t>(cWP ? 2 : 0);
  tri_[nb].v = {q, w, v};
  tri_[nb].n = {t2, nb2, nQW};
  tri_[nb].c = static_cast<std::uint8_t>(cQW ? 4 : 0);
  tri_[nb2].v = {q, v, u};
  tri_[nb2].n = {t, nUQ, nb};
  tri_[nb2].c = static_cast<std::uint8_t>(cUQ ? 2 : 0);
  if (nWP >= 0) setNbrAcross(nWP, w, p, t2);
  if (nUQ >= 0) setNbrAcross(nUQ, u, q, nb2);
  ++stamp_[t];
  ++stamp_[nb];
  tq_[t] = q1;
  tq_[t2] = q2;
  tq_[nb] = q3;
  tq_[nb2] = q4;
  vtri_[p] = vtri_[u] = t;
  vtri_[w] = t2;
  vtri_[q] = nb;
  vdirty_[p] = vdirty_[u] = vdirty_[w] = vdirty_[q] = 1;
  for (const int k : {t, t2, nb, nb2}) touched.push_back(k);
  return true;
}

// Calls op(t, i, u, w) on the unconstrained edges (u, w) opposite vertex i of every live
// triangle t, or of those in list; a full scan visits each edge once (from the side where
// u < w). op returns true when it changed the mesh around t, which ends t's scan.
// Returns how many calls changed the mesh.
template <class EdgeOp>
int Mesher::scanEdges(const std::vector<int>* list, EdgeOp&& op) {
  int changed = 0;
  const int n = list ? static_cast<int>(list->size()) : static_cast<int>(tri_.size());
  for (int k = 0; k < n; ++k) {
    const int t = list ? (*list)[k] : k;
    tickProgress();
    if (tri_[t].v[0] < 0) continue;
    for (int i = 0; i < 3; ++i) {
      const int u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
      if ((!list && u > w) || cons(t, i)) continue;
      if (op(t, i, u, w)) {
        ++changed;
        break;  // t changed or is gone
      }
    }
  }
  return changed;
}

bool Mesher::collapseEdge(int u, int w, MergedPlace place, std::vector<int>& touched) {
  if (!vbnd_[u] && !vbnd_[w]) {  // two free ends: merged at a new place first
    bool done = false;
    if (place != MergedPlace::Midpoint) {
      colOptimal_ = true;
      colSearch_ = place == MergedPlace::Searched;
      done = tryCollapse(u, w, true, touched);
      colOptimal_ = colSearch_ = false;
    }
    if (done || (place != MergedPlace::Searched && tryCollapse(u, w, true, touched))) return true;
  }
  return tryCollapse(u, w, false, touched) || tryCollapse(w, u, false, touched);
}

// Collapses edges shorter than kCollapseLength (fronts meeting leave some), removing an
// inner end point (onto the midpoint when both ends are inner, else onto the other end),
// and splits inner edges longer than kSplitLength (new edges wait for the next pass).
// Scans every triangle, or only those in list (whose edges changed since the last scan).
int Mesher::lengthPass(const std::vector<int>* list, std::vector<int>& touched) {
  return scanEdges(list, [&](int t, int i, int u, int w) {
    const double len = SymMt::average2(vx_[u].m, vx_[w].m).length(vx_[w].p - vx_[u].p);
    if (len < kCollapseLength) {
      return collapseEdge(u, w, MergedPlace::Midpoint, touched);
    }
    return len > kSplitLength && tri_[t].n[i] >= 0 && trySplit(t, i, touched);
  });
}

// Final rounds over every edge still shorter than kCollapseLength (the adaptation loop's
// collapses keep new edges under kCollapseMaxLength, which leaves some where fronts
// met): collapse onto the unit-length point of the merged ring, else the midpoint, else
// either end, with new edges up to kFinalCollapseMaxLength and no triangle below
// kFinalCollapseMinQuality (or below the worst one before).
// Scans every triangle, or only those in list (whose edges changed since the last scan).
int Mesher::shortEdgePass(const std::vector<int>* list, std::vector<int>& touched) {
  colMaxLength_ = kFinalCollapseMaxLength;
  colMinQuality_ = kFinalCollapseMinQuality;
  const int changed = scanEdges(list, [&](int, int, int u, int w) {
    if (!(SymMt::average2(vx_[u].m, vx_[w].m).length(vx_[w].p - vx_[u].p) < kCollapseLength)) return false;
    return collapseEdge(u, w, MergedPlace::UnitLengthThenMidpoint, touched);
  });
  colMaxLength_ = kCollapseMaxLength;
  colMinQuality_ = kCollapseMinQuality;
  return changed;
}

}  // namespace planar
}  // namespace anisomesh

// Planar mesher: length-bounded node smoothing.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

// Moves every free vertex towards the point its neighbours see at unit metric distance
// (or halfway), when no triangle of its ball gets inverted and the worst one improves.
int Mesher::smoothPass(std::vector<int>& touched) {
  int moved = 0;
  std::vector<int> ring, ballTri;
  std::vector<SymMt> edgeM, triM;
  const int nv = static_cast<int>(vx_.size());
  // The vertices with a triangle below kSmoothSkipQuality around them, marked once: only
  // they are smoothed, and the pass leaves tq_ as it is (moves only queue their triangles
  // in `touched`), so the others need no walk around their ball to be skipped.
  std::vector<char> poor(nv, 0);
  for (size_t t = 0; t < tri_.size(); ++t) {
    const auto& tv = tri_[t].v;
    if (tv[0] >= 0 && tq_[t] < kSmoothSkipQuality) poor[tv[0]] = poor[tv[1]] = poor[tv[2]] = 1;
  }
  for (int v = kSuper; v < nv; ++v) {
    tickProgress();
    if (vbnd_[v] || !vdirty_[v]) continue;  // clean: nothing around it changed since its last visit
    if (!poor[v]) {                         // already good: not worth the metric queries
      vdirty_[v] = 0;
      continue;
    }
    if (!closedBall(v, ballTri, ring)) continue;
    double before = std::numeric_limits<double>::infinity();
    for (const int bt : ballTri) before = std::min(before, tq_[bt]);
    vdirty_[v] = 0;
    if (before >= kSmoothSkipQuality) continue;  // already good: not worth the metric queries
    const Vec2 p = vx_[v].p;
    const size_t deg = ring.size();
    // The vertex keeps its metric while the candidates are judged: computed once.
    ballMetrics(v, ring, edgeM, triM);
    Vec2 target(0.0, 0.0);
    double longest = kSplitLength;  // no ring edge may end up longer (or longer than the longest now)
    // Nor shorter than kSmoothMinLength (or than the shortest now): smoothing would
    // otherwise leave short edges that no later pass collapses.
    double shortest = kSmoothMinLength;
    for (size_t k = 0; k < deg; ++k) {
      const Vec2 dv = p - vx_[ring[k]].p;
      const double len = edgeM[k].length(dv);
      longest = std::max(longest, len);
      shortest = std::min(shortest, len);
      target += len > 0.0 ? Vec2(vx_[ring[k]].p + dv / len) : p;
    }
    target /= static_cast<double>(deg);
    // Candidates in order of preference: unit-length target (edge lengths), halfway to it,
    // then the ring centroid (Laplacian; the same in any constant metric) and halfway to
    // it as fallbacks for the worst balls; the first that improves the worst triangle wins.
    Vec2 centroid(0.0, 0.0);
    for (const int r : ring) centroid += vx_[r].p;
    centroid /= static_cast<double>(ring.size());
    const Vec2 cands[4] = {target, 0.5 * (p + target), centroid, 0.5 * (p + centroid)};
    int best = -1;
    double bestQ = before + kSmoothMinGain;  // tiny gains are not worth re-dirtying the ring
    for (int ci = 0; ci < 4; ++ci) {
      const Vec2& cand = cands[ci];
      double after = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < deg; ++k) {
        after = std::min(after,
                         metricTriangleQuality(triM[k], cand, vx_[ring[k]].p, vx_[ring[k + 1 == deg ? 0 : k + 1]].p));
        if (after <= bestQ) break;
      }
      if (!(after > bestQ)) continue;
      bool fits = true;
      for (size_t k = 0; k < deg && fits; ++k) {
        const double l = edgeM[k].length(cand - vx_[ring[k]].p);
        fits = l <= longest && l >= shortest;
      }
      if (!fits) continue;
      bool valid = true;
      for (size_t k = 0; k < deg && valid; ++k)
        valid = orient(cand, vx_[ring[k]].p, vx_[ring[k + 1 == deg ? 0 : k + 1]].p) > 0.0;
      if (!valid) continue;
      best = ci;
      bestQ = after;
      break;
    }
    if (best < 0) continue;
    for (const int r : ring) vdirty_[r] = 1;
    vdirty_[v] = 1;
    vx_[v].p = cands[best];
    int hint = hintOf(v);
    vx_[v].m = queryMetric(cands[best], hint);
    vhint_[v] = hint;
    for (size_t k = 0; k < ballTri.size(); ++k) touched.push_back(ballTri[k]);
    ++moved;
  }
  return moved;
}

}  // namespace planar
}  // namespace anisomesh

// Planar mesher: metric edge swaps.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

// One sweep of metric-quality edge swaps over the triangles in work; flipped triangles
// go to next (they are the only ones whose edges can have become swappable).
// An edge is judged from both of its triangles when both are in work: the second judgement
// is skipped when the first kept the edge and neither triangle flipped since (the same
// vertices, metrics and qualities give the same answer), which halves the first sweep's
// judgements.
int Mesher::swapSweep(const std::vector<int>& work, std::vector<int>& next) {
  int swaps = 0;
  if (swapSeen_.size() < tri_.size()) swapSeen_.resize(tri_.size(), SwapSeen{0, 0});
  if (swapClock_ > 0xf0000000u - static_cast<std::uint32_t>(work.size())) {  // before the clock wraps
    std::fill(swapSeen_.begin(), swapSeen_.end(), SwapSeen{0, 0});
    swapClock_ = 0;
  }
  const std::uint32_t sweepStart = swapClock_ + 1;
  for (const int t : work) {
    tickProgress();
    if (tri_[t].v[0] < 0) continue;
    const std::uint32_t now = ++swapClock_;
    swapSeen_[t].visit = now;
    for (int i = 0; i < 3; ++i) {
      const int nb = tri_[t].n[i];
      if (nb < 0 || cons(t, i)) continue;
      const double before = std::min(tq_[t], tq_[nb]);
      if (before >= kSwapSkipQuality) continue;  // both nearly ideal: nothing to gain
      // nb was visited in this sweep without flipping, and neither flipped since: it (or an
      // earlier visit, by this rule) judged this edge then and kept it. Not with a NaN
      // quality: std::min then depends on the side it is judged from.
      const SwapSeen& seen = swapSeen_[nb];
      if (seen.visit >= sweepStart && seen.flip < seen.visit && swapSeen_[t].flip < seen.visit && !std::isnan(tq_[t]) &&
          !std::isnan(tq_[nb]))
        continue;
      const int p = tri_[t].v[i], u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
      int j = 0;
      while (tri_[nb].v[j] == u || tri_[nb].v[j] == w) ++j;
      const int q = tri_[nb].v[j];
      const double qa = triQuality(p, u, q);
      if (!(qa > before + 1e-6)) continue;
      const double qb = triQuality(q, w, p);
      if (!(qb > before + 1e-6)) continue;
      // Positive metric quality means counter-clockwise in floating point; confirm exactly.
      if (orient(vx_[p].p, vx_[u].p, vx_[q].p) <= 0.0 || orient(vx_[q].p, vx_[w].p, vx_[p].p) <= 0.0) continue;
      flip(t, i);
      swapSeen_[t].flip = swapSeen_[nb].flip = now;
      tq_[t] = qa;
      tq_[nb] = qb;
      next.push_back(t);
      next.push_back(nb);
      ++swaps;
      break;  // t changed; its edges are seen again in the next sweep
    }
  }
  return swaps;
}

}  // namespace planar
}  // namespace anisomesh

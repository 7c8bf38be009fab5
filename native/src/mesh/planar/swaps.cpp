// Planar mesher: metric edge swaps.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

// One sweep of metric-quality edge swaps over the triangles in work; flipped triangles
// go to next (they are the only ones whose edges can have become swappable).
int Mesher::swapSweep(const std::vector<int>& work, std::vector<int>& next) {
  int swaps = 0;
  for (const int t : work) {
    tickProgress();
    if (tri_[t].v[0] < 0) continue;
    for (int i = 0; i < 3; ++i) {
      const int nb = tri_[t].n[i];
      if (nb < 0 || cons(t, i)) continue;
      const int p = tri_[t].v[i], u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
      int j = 0;
      while (tri_[nb].v[j] == u || tri_[nb].v[j] == w) ++j;
      const int q = tri_[nb].v[j];
      const double before = std::min(tq_[t], tq_[nb]);
      if (before >= kSwapSkipQuality) continue;  // both nearly ideal: nothing to gain
      const double qa = triQuality(p, u, q);
      if (!(qa > before + 1e-6)) continue;
      const double qb = triQuality(q, w, p);
      if (!(qb > before + 1e-6)) continue;
      // Positive metric quality means counter-clockwise in floating point; confirm exactly.
      if (orient(vx_[p].p, vx_[u].p, vx_[q].p) <= 0.0 || orient(vx_[q].p, vx_[w].p, vx_[p].p) <= 0.0) continue;
      flip(t, i);
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

// Planar mesher: the worst triangles polished by a pattern search on their free vertices.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

// The smoothing pass tries four fixed candidates per vertex; a free vertex of a triangle
// still below kPolishQuality after the adaptation loop gets a compass search instead: steps
// of kPolishFirstStep metric units in eight directions, halved down to kPolishLastStep, each
// move taken when the worst triangle of the ball improves, each ring edge stays within
// [kPolishMinLength, kPolishMaxLength] (or within its present length) and the ball's
// quality sum loses at most kPolishSumSlack per triangle; the place found is kept when it
// still wins under the metric queried there. Returns the vertices moved; their balls go to
// touched (with their qualities refreshed).
int Mesher::polishPass(std::vector<int>& touched) {
  std::vector<int> candidates;
  ++epoch_;
  if (vmark_.size() < vx_.size()) vmark_.resize(vx_.size() + 1024, 0);
  for (int t = 0; t < static_cast<int>(tri_.size()); ++t) {
    if (tri_[t].v[0] < 0 || !(tq_[t] < kPolishQuality)) continue;
    for (const int v : tri_[t].v)
      if (!vbnd_[v] && vmark_[v] != epoch_) {
        vmark_[v] = epoch_;
        candidates.push_back(v);
      }
  }
  std::sort(candidates.begin(), candidates.end());  // vertex order: the same for any triangle order
  int moved = 0;
  std::vector<int> ring, ballTri;
  std::vector<SymMt> edgeM, triM;
  std::vector<double> len0;  // ring edge lengths before the move
  for (const int v : candidates) {
    tickProgress();
    if (!closedBall(v, ballTri, ring)) continue;
    const size_t deg = ring.size();
    double before = std::numeric_limits<double>::infinity();
    for (const int bt : ballTri) before = std::min(before, tq_[bt]);
    if (!(before < kPolishQuality)) continue;  // an earlier move in this pass fixed it
    ballMetrics(v, ring, edgeM, triM);
    len0.resize(deg);
    const Vec2 p0 = vx_[v].p;
    for (size_t k = 0; k < deg; ++k) len0[k] = edgeM[k].length(p0 - vx_[ring[k]].p);
    // The ball's worst quality with v at x under the fixed metrics, or -1 when x inverts a
    // triangle or puts a ring edge out of bounds.
    double sumFloor = -std::numeric_limits<double>::infinity();
    auto ballQuality = [&](const Vec2& x, double* sumOut = nullptr) {
      double q = std::numeric_limits<double>::infinity(), sum = 0.0;
      for (size_t k = 0; k < deg; ++k) {
        const Vec2& a = vx_[ring[k]].p;
        const Vec2& b = vx_[ring[k + 1 == deg ? 0 : k + 1]].p;
        if (!(orient(x, a, b) > 0.0)) return -1.0;
        // Each ring edge within bounds a little inside [1/sqrt2, sqrt2] (or within its
        // present length): the final check under the new metric then rarely refuses.
        const double l = edgeM[k].length(x - a);
        if (!(l <= std::max(kPolishMaxLength, len0[k]) && l >= std::min(kPolishMinLength, len0[k]))) return -1.0;
        const double qk = metricTriangleQuality(triM[k], x, a, b);
        if (!(qk > 0.0)) return -1.0;  // also NaN
        q = std::min(q, qk);
        sum += qk;
      }
      if (sumOut) *sumOut = sum;
      return sum < sumFloor ? -1.0 : q;
    };
    Vec2 best = p0;
    double sum0 = 0.0;
    double bestQ = ballQuality(p0, &sum0);
    if (!(bestQ >= 0.0)) continue;
    // The ball's other triangles pay for its worst one, within kPolishSumSlack each.
    sumFloor = sum0 - kPolishSumSlack * static_cast<double>(deg);
    const SymMt& m = vx_[v].m;
    bestQ = compassSearch(m, best, bestQ, [&](const Vec2& x) { return ballQuality(x); });
    if (!(bestQ > before + kSmoothMinGain)) continue;
    // Judged again under the metric at the new place, as the next passes and the quality
    // report see it: the worst triangle better, no ring edge newly outside [1/sqrt2, sqrt2].
    int hint = hintOf(v);
    const SymMt mNew = queryMetric(best, hint);
    double after = std::numeric_limits<double>::infinity(), sumBefore = 0.0, sumAfter = 0.0;
    bool lengthsKept = true;
    for (size_t k = 0; k < deg && lengthsKept; ++k) {
      const int r1 = ring[k], r2 = ring[k + 1 == deg ? 0 : k + 1];
      const double q = metricTriangleQuality(SymMt::average3(mNew, vx_[r1].m, vx_[r2].m), best, vx_[r1].p, vx_[r2].p);
      after = std::min(after, q);
      sumAfter += q;
      sumBefore += tq_[ballTri[k]];
      const double l = SymMt::average2(mNew, vx_[r1].m).length(best - vx_[r1].p);
      lengthsKept = l <= std::max(kSplitLength, len0[k]) && l >= std::min(kCollapseLength, len0[k]);
    }
    if (!lengthsKept || !(after > before + kSmoothMinGain) ||
        sumAfter < sumBefore - kPolishSumSlack * static_cast<double>(deg))
      continue;
    vx_[v].p = best;
    vx_[v].m = mNew;
    vhint_[v] = hint;
    for (const int r : ring) vdirty_[r] = 1;
    vdirty_[v] = 1;
    for (const int bt : ballTri) {
      tq_[bt] = triQuality(tri_[bt].v[0], tri_[bt].v[1], tri_[bt].v[2]);
      touched.push_back(bt);
    }
    ++moved;
  }
  return moved;
}

}  // namespace planar
}  // namespace anisomesh

// Planar mesher: the adaptation loop (swaps, collapses, splits, smoothing on the edges
// that changed).
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

void Mesher::improve() {
  vdirty_.assign(vx_.size(), 1);
  const int nt = static_cast<int>(tri_.size());
  tq_.assign(nt, 0.0);
  std::vector<int> work, next;
  for (int t = 0; t < nt; ++t)
    if (tri_[t].v[0] >= 0) {
      tq_[t] = triQuality(tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]);
      work.push_back(t);
    }
  // Removes repeated triangles keeping the first occurrence (deterministic, no sort).
  auto dedupe = [&](std::vector<int>& list) {
    ++epoch_;
    size_t k = 0;
    for (const int t : list)
      if (tri_[t].mark != epoch_) {
        tri_[t].mark = epoch_;
        list[k++] = t;
      }
    list.resize(k);
  };
  // Triangles whose edges changed since the last length scan (collapse/split candidates).
  std::vector<int> scan, changed;
  // Sweeps until no swap is left (each sweep visits only the triangles the last one flipped,
  // so the cost follows the swaps made): a chain of improving swaps cut short leaves its
  // slivers for good, since later passes revisit only what they changed.
  auto swaps = [&] {
    for (int k = 0; k < kMaxSwapSweeps && !work.empty(); ++k) {
      next.clear();
      swapSweep(work, next);
      changed.insert(changed.end(), next.begin(), next.end());
      dedupe(next);
      work.swap(next);
    }
  };
  // Adaptation loop: swaps, collapse of short edges and split of long ones, swaps, smoothing;
  // the first pass looks at every edge, the later ones at the edges that changed.
  for (int pass = 0; pass < opt_.improvementPasses; ++pass) {
    swaps();
    work.clear();
    const std::vector<int>* list = pass == 0 ? nullptr : &scan;
    const int resized = lengthPass(list, work);
    dedupe(work);
    changed.insert(changed.end(), work.begin(), work.end());
    swaps();
    work.clear();
    const int moved = smoothPass(work);
    // The ball triangles of moved vertices are reconsidered for swaps (the vertex metric
    // changed too, so their cached quality is refreshed).
    dedupe(work);
    for (const int t : work) tq_[t] = triQuality(tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]);
    changed.insert(changed.end(), work.begin(), work.end());
    scan.swap(changed);
    changed.clear();
    dedupe(scan);
    checkProgress(0.8 + 0.15 * (pass + 1) / opt_.improvementPasses);
    if (resized == 0 && moved == 0) break;  // converged
  }
  if (opt_.improvementPasses > 0) swaps();
  // Final short-edge rounds, each followed by swaps and a smoothing of the changed balls;
  // the first round scans every edge, the next ones the edges that changed.
  for (int round = 0; round < kFinalCollapseRounds && opt_.improvementPasses > 0; ++round) {
    work.clear();
    changed.clear();
    const int collapsed = shortEdgePass(round == 0 ? nullptr : &scan, work);
    if (collapsed == 0) break;
    dedupe(work);
    changed.insert(changed.end(), work.begin(), work.end());
    swaps();
    work.clear();
    smoothPass(work);
    dedupe(work);
    for (const int t : work) tq_[t] = triQuality(tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]);
    changed.insert(changed.end(), work.begin(), work.end());
    swaps();
    scan.swap(changed);
    dedupe(scan);
  }
  // The worst triangles left: their free vertices searched for a better place.
  for (int round = 0; round < kPolishRounds && opt_.improvementPasses > 0; ++round) {
    work.clear();
    if (polishPass(work) == 0) break;
    dedupe(work);
    swaps();
  }
  // Triangles polishing could not raise: one of their short edges collapsed, then swaps on
  // the changed triangles and a polish round (of every triangle still poor).
  for (int round = 0; round < kRepairRounds && opt_.improvementPasses > 0; ++round) {
    work.clear();
    if (repairPass(work) == 0) break;
    dedupe(work);
    swaps();
    work.clear();
    polishPass(work);
    dedupe(work);
    swaps();
  }
}

}  // namespace planar
}  // namespace anisomesh

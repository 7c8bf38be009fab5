// Planar mesher: the worst triangles repaired by collapsing one of their short edges.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

void Mesher::placeMergedVertex(const std::vector<int>& ring, int k1, int k2, const std::vector<int>& ballB, int b,
                               Vec2& pb, SymMt& mb) {
  const int deg = static_cast<int>(ring.size());
  colFan_.clear();
  for (int k = 0; k < deg; ++k)
    if (k != k1 && k != k2) colFan_.push_back({ring[k], ring[(k + 1) % deg]});
  for (const int u : ballB) {
    const auto& tv = tri_[u].v;
    const int i = tv[0] == b ? 0 : (tv[1] == b ? 1 : 2);
    colFan_.push_back({tv[next3(i)], tv[prev3(i)]});
  }
  // The fan's worst quality with the merged vertex at x (metric mb), or -1 when x inverts a
  // triangle or puts an edge out of bounds (each fan vertex starts one triangle).
  auto worst = [&](const Vec2& x) {
    double q = std::numeric_limits<double>::infinity();
    for (const auto& [r, c] : colFan_) {
      if (!(orient(x, vx_[r].p, vx_[c].p) > 0.0)) return -1.0;
      const double l = SymMt::average2(mb, vx_[r].m).length(vx_[r].p - x);
      if (!(l >= kCollapseLength && l <= colMaxLength_)) return -1.0;
      const double qk = metricTriangleQuality(SymMt::average3(mb, vx_[r].m, vx_[c].m), x, vx_[r].p, vx_[c].p);
      if (!(qk > 0.0)) return -1.0;  // also NaN
      q = std::min(q, qk);
    }
    return q;
  };
  Vec2 best = pb;
  compassSearch(mb, best, worst(pb), worst);
  if (best != pb) {
    pb = best;
    mb = queryMetric(pb);
  }
}

// Polishing moves one free vertex at a time, so a triangle caught between a short and a
// long edge (a front meeting a boundary, a steep gradation) can stay poor: every place of
// its free vertex spoils a neighbour. Removing a vertex changes the topology instead. Each
// triangle below kRepairQuality, worst first, has its edges shorter than
// kRepairCollapseLength collapsed (shortest first; for two free ends onto the place the
// compass search finds from the unit-length point of the merged ring, else onto either
// end), taken only when every new triangle beats the worst one of the balls before by
// kRepairMinGain and no new edge is longer than kFinalCollapseMaxLength. Returns the
// collapses made; their triangles go to touched.
int Mesher::repairPass(std::vector<int>& touched) {
  std::vector<std::pair<double, int>> poor;
  for (int t = 0; t < static_cast<int>(tri_.size()); ++t)
    if (tri_[t].v[0] >= 0 && tq_[t] < kRepairQuality) poor.push_back({tq_[t], t});
  std::sort(poor.begin(), poor.end());  // worst first, ties by index: deterministic
  // The collapse limits of the repair, the adaptation loop's back on every way out.
  struct Limits {
    Mesher& m;
    ~Limits() {
      m.colMaxLength_ = kCollapseMaxLength;
      m.colMinQuality_ = kCollapseMinQuality;
      m.colMinGain_ = 0.0;
      m.colOptimal_ = m.colSearch_ = false;
    }
  } restore{*this};
  colMaxLength_ = kFinalCollapseMaxLength;
  colMinQuality_ = std::numeric_limits<double>::infinity();  // the floor is the balls' worst
  colMinGain_ = kRepairMinGain;
  int repaired = 0;
  for (const auto& [q, t] : poor) {
    tickProgress();
    if (tri_[t].v[0] < 0 || tq_[t] != q) continue;  // an earlier repair changed it
    std::array<std::pair<double, int>, 3> edges;
    for (int i = 0; i < 3; ++i) {
      const int u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
      edges[i] = {SymMt::average2(vx_[u].m, vx_[w].m).length(vx_[w].p - vx_[u].p), i};
    }
    std::sort(edges.begin(), edges.end());
    for (const auto& [len, i] : edges) {
      if (!(len < kRepairCollapseLength) || cons(t, i)) continue;
      if (collapseEdge(tri_[t].v[next3(i)], tri_[t].v[prev3(i)], MergedPlace::Searched, touched)) {
        ++repaired;
        break;
      }
    }
  }
  return repaired;
}

}  // namespace planar
}  // namespace anisomesh

#pragma once
// Private header of the planar mesher (one class, its operations in one file each under
// mesh/planar/): metric Delaunay meshing of a planar domain by the coordinate-transformation
// approach. Exact Delaunay triangulation of the boundary points in a super-box
// (boundary_recovery.cpp), boundary recovery by edge flips, removal of outside triangles by
// parity flood fill, frontal-Delaunay insertion of inner nodes in the metric (insertion.cpp:
// Rebay-style point placement, Bowyer-Watson cavities judged by each triangle's metric
// circumcircle; the kernel in delaunay_kernel.cpp), then an adaptation loop
// (improvement.cpp): metric edge swaps (swaps.cpp), collapse of short edges and split of
// long inner edges (collapse_split.cpp), length-bounded node smoothing (smoothing.cpp), each
// pass on the edges that changed, and last a compass search on the vertices of the worst
// triangles (polish.cpp). Data layout is flat arrays of triangle records with
// neighbour indices (topology.cpp); no per-insertion heap allocation on the hot path; the
// vertices are renumbered along a Hilbert curve (renumbering.cpp) before the improvement
// passes for cache locality. The driver, Mesher::run, is mesh/planar_mesher.cpp.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../mesh_internal.h"
#include "anisomesh/core/clock.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/int_conversion.h"
#include "anisomesh/mesh/planar_mesher.h"
#include "anisomesh/mesh/predicates.h"

namespace anisomesh {
namespace planar {

constexpr int kSuper = 4;                                // super-box corners are vertices 0..3
constexpr double kIdealRadius = 0.57735026918962576;     // circumradius of the unit equilateral triangle
constexpr double kAcceptRadius = 0.70710678118654752;    // triangles with metric radius below are done
constexpr double kRetryRadius = 1.5;                     // larger ones try their circumcentre before giving up
constexpr int kBucketOffset = 4 * 1100;                  // bucket index offset: covers every double exponent
constexpr double kEstimateFactor = 1.0;                  // measured: within ~10% on the layer test cases
constexpr double kCoarseEstimateLimit = 65536.0;         // larger meshes take the fine estimate (metric_area.cpp)
constexpr double kSwapSkipQuality = 0.97;                // pairs whose worse triangle is better are not swapped
constexpr double kCollapseLength = 0.70710678118654752;  // shorter edges are collapsed
constexpr double kCollapseMaxLength = 1.3;               // ... unless a new edge would be longer
constexpr double kCollapseMinQuality = 0.4;              // ... or a triangle worse than this (or than before)
// Final short-edge rounds (after the adaptation loop): the edges still shorter than
// kCollapseLength are collapsed where the merged vertex can sit at unit length from its
// ring, new edges up to kFinalCollapseMaxLength (just under sqrt2) but no triangle below
// kFinalCollapseMinQuality (or below the worst one before).
constexpr double kFinalCollapseMaxLength = 1.41;
constexpr double kFinalCollapseMinQuality = 0.75;
constexpr int kFinalCollapseRounds = 2;
constexpr double kSplitLength = 1.41421356237309505;  // longer inner edges are split at their midpoint
constexpr double kSplitMinQuality = 0.4;              // ... unless a triangle gets worse than this (and than before)
constexpr double kSmoothSkipQuality = 0.9;            // balls whose worst triangle is better are not smoothed
constexpr double kSmoothMinGain = 0.005;              // smaller gains of the worst triangle are not taken
// Smoothing makes no ring edge shorter than this (unless it already is): a little above
// 1/sqrt2, as the vertex-averaged Mt overestimates the length integral in a graded metric.
constexpr double kSmoothMinLength = 0.715;

// Polishing (polish.cpp): vertices of triangles below kPolishQuality after the adaptation
// loop get a compass search in metric space, steps from kPolishFirstStep down to
// kPolishLastStep metric units, for kPolishRounds rounds (each followed by swaps).
constexpr double kPolishQuality = 0.8;
constexpr double kPolishFirstStep = 0.25;
constexpr double kPolishLastStep = 1.0 / 64.0;
constexpr int kPolishRounds = 2;
// Search bounds of each ring edge (or its present length if outside): a little inside
// [1/sqrt2, sqrt2], which the place found must keep under the metric queried there.
constexpr double kPolishMinLength = 0.73, kPolishMaxLength = 1.38;
// The ball's other triangles may lose this much quality each (summed over the ball).
constexpr double kPolishSumSlack = 0.01;
// Eight unit directions (metric space), every 45 degrees: the compass search's moves.
constexpr double kCompassDiag = 0.70710678118654752;
constexpr double kCompassDirs[8][2] = {{1, 0},  {kCompassDiag, kCompassDiag},   {0, 1},  {-kCompassDiag, kCompassDiag},
                                       {-1, 0}, {-kCompassDiag, -kCompassDiag}, {0, -1}, {kCompassDiag, -kCompassDiag}};
// Repair (repair.cpp): triangles still below kRepairQuality after polishing lose one of
// their edges shorter than kRepairCollapseLength when every new triangle beats the worst
// one before by kRepairMinGain.
constexpr double kRepairQuality = 0.8;
constexpr double kRepairCollapseLength = 1.0;
constexpr double kRepairMinGain = 0.01;
constexpr int kRepairRounds = 2;

// Compass search in metric space from x (score0 = score(x)): steps of kPolishFirstStep
// down to kPolishLastStep metric units under m in the eight kCompassDirs, each move taken
// when score (negative: refused) rises by more than 1e-9. Returns the best score; x is
// moved to its place.
template <class Score>
double compassSearch(const SymMt& m, Vec2& x, double score0, Score&& score) {
  double best = score0;
  for (double step = kPolishFirstStep; step >= kPolishLastStep; step *= 0.5) {
    bool improved = true;
    for (int moves = 0; improved && moves < 32; ++moves) {  // 32: a bound only
      improved = false;
      for (const auto& d : kCompassDirs) {
        const Vec2 y = x + m.solve(Vec2(step * d[0], step * d[1]));
        if (!y.allFinite()) continue;
        const double q = score(y);
        if (q > best + 1e-9) {
          best = q;
          x = y;
          improved = true;
        }
      }
    }
  }
  return best;
}

// Swap sweeps per call, a bound only: chains along a boundary that crosses a stretched layer
// obliquely took 11 to 18 sweeps (6 left fans of slivers, min Q 0.02).
constexpr int kMaxSwapSweeps = 256;

// Elements of a metric area: one unit equilateral triangle per sqrt(3)/4 of it.
inline double trianglesOfMetricArea(double area) { return kEstimateFactor * area / (std::sqrt(3.0) / 4.0); }

inline int next3(int i) { return i == 2 ? 0 : i + 1; }

// orient2d (predicates.h) with its floating-point filter inlined, the same value: the
// hot predicate of point location and cavity checks; the exact evaluation stays out of line.
inline double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kBound = (3.0 + 16.0 * kEps) * kEps;
  const double detleft = (a.x() - c.x()) * (b.y() - c.y());
  const double detright = (a.y() - c.y()) * (b.x() - c.x());
  const double det = detleft - detright;
  const double bound = kBound * (std::fabs(detleft) + std::fabs(detright));
  if (det > bound || -det > bound) return det;
  return orient2d(a, b, c);
}
inline int prev3(int i) { return i == 0 ? 2 : i - 1; }

// Metric-space circumcircle of a triangle under its own (vertex-averaged) metric.
struct TriCache {
  double cx = 0, cy = 0;  // physical circumcentre
  double r2 = 0;          // squared metric radius
  SymMt m;                // the triangle's metric
};

class Mesher {
 public:
  Mesher(const std::vector<BoundaryLoop>& loops, const ControlSpace& cs, const PlanarMesherOptions& opt)
      : loops_(loops), cs_(cs), opt_(opt) {}

  // Validates, triangulates the boundary and estimates the element count (the budget
  // checked): returns the estimate. Then finish() meshes the inside.
  double start();
  Mesh finish();
  Mesh run() {
    start();
    return finish();
  }
  // After the parts of a decomposed domain are merged: swaps and polish rounds on the
  // triangles around the cut vertices [seamBegin, seamEnd) of merged (seam_polish.cpp).
  void polishSeam(Mesh& merged, int seamBegin, int seamEnd);

 private:
  // ---- setup and output ----
  void validate() const;
  void checkProgress(double fraction);
  // The progress callback again, at the last fraction, every 4096 steps of a long sweep
  // (one improvement pass over a million triangles is seconds of work in wasm).
  void tickProgress() {
    if (opt_.progress && (++progressTicks_ & 4095) == 0) checkProgress(lastFraction_);
  }
  std::uint64_t progressTicks_ = 0;
  double lastFraction_ = 0.0;
  // The control space's walk starts where the last query ended (queries come in spatial order).
  SymMt queryMetric(const Vec2& p) const { return queryMetric(p, queryHint_); }
  // ... or at `hint` (updated to where the walk ended): vertex hints (vhint_) for a point
  // next to a vertex, which the last query, made elsewhere, is often not (metricAtNear
  // gives the same value from any start).
  SymMt queryMetric(const Vec2& p, int& hint) const { return SymMt::from(cs_.metricAtNear(p, hint).transform()); }
  // A copy of vertex v's hint (the control-space element its metric was located in).
  int hintOf(int v) const { return vhint_[static_cast<size_t>(v)]; }
  mutable int queryHint_ = -1;
  Mesh output() const;

  // ---- triangle storage ----
  int allocTri();
  // The triangles around v counter-clockwise and, for each, its vertex after v; false when
  // v's ball is open (a boundary vertex) or longer than 1000 triangles.
  bool closedBall(int v, std::vector<int>& tris, std::vector<int>& ring) const;
  // For v's ring (closedBall): the metric of each ring edge (v, ring[k]) and of each ball
  // triangle (v, ring[k], ring[k + 1]), as vertex averages with v's present metric.
  void ballMetrics(int v, const std::vector<int>& ring, std::vector<SymMt>& edgeM, std::vector<SymMt>& triM) const;
  void setNbrAcross(int tri, int a, int b, int newNbr);  // in tri, edge (b, a) now borders newNbr
  bool cons(int t, int i) const { return (tri_[t].c >> i) & 1; }
  int findEdge(int a, int b, int* idx) const;  // triangle holding directed edge a->b, opposite index
  int liveTriangles() const { return static_cast<int>(tri_.size() - freeTris_.size()); }

  // ---- Delaunay kernel ----
  int locate(const Vec2& x, int start, bool stopAtConstraints);
  template <class InCircle>
  bool buildCavity(const Vec2& x, int t0, InCircle inCircle);
  int commitCavity(int v);  // fans the cavity from vertex v, returns one new triangle
  void flip(int t, int i);

  // ---- stages ----
  // The boundary triangulation (boundary points, recovered edges, outside removed): from
  // opt_.boundaryCache when it holds loops equal to loops_, else built (and stored there by
  // a boundary-only run).
  void boundaryTriangulation();
  // A boundary-only run, done: its triangulation moves to opt_.boundaryCache (if any).
  void keepBoundaryTriangulation();
  void triangulateBoundary();
  void recoverEdge(int a, int b);
  void removeOutside();
  double estimateMetricArea();
  double metricAreaEstimate(std::int64_t subdivisions, int maxRows) const;
  double metricAreaRec(const Vec2& a, const Vec2& b, const Vec2& c, double da, double db, double dc, int depth,
                       std::int64_t& budget, int& hint) const;
  void insertInnerNodes();
  void renumberSpatially();
  void improve();
  int swapSweep(const std::vector<int>& work, std::vector<int>& next);
  int smoothPass(std::vector<int>& touched);
  int polishPass(std::vector<int>& touched);
  int repairPass(std::vector<int>& touched);
  template <class EdgeOp>
  int scanEdges(const std::vector<int>* list, EdgeOp&& op);
  int lengthPass(const std::vector<int>* list, std::vector<int>& touched);
  bool tryCollapse(int a, int b, bool toMidpoint, std::vector<int>& touched);
  // Where collapseEdge merges two free ends: the midpoint; the unit-length point of the
  // merged ring, else the midpoint; that point moved by placeMergedVertex (no midpoint).
  enum class MergedPlace { Midpoint, UnitLengthThenMidpoint, Searched };
  // Collapses edge (u, w): two free ends merged at `place`, else u onto w, else w onto u.
  bool collapseEdge(int u, int w, MergedPlace place, std::vector<int>& touched);
  // For a midpoint collapse (tryCollapse's a onto b, ring and k1, k2 as there, ballB: b's
  // other triangles): pb moved by a compass search to where the merged fan's worst triangle
  // is best, its edges within [kCollapseLength, colMaxLength_]; mb queried there.
  void placeMergedVertex(const std::vector<int>& ring, int k1, int k2, const std::vector<int>& ballB, int b, Vec2& pb,
                         SymMt& mb);
  int shortEdgePass(const std::vector<int>* list, std::vector<int>& touched);
  bool trySplit(int t, int i, std::vector<int>& touched);

  // ---- metric helpers ----
  void computeCache(int t);
  double triQuality(int a, int b, int c) const;
  double triQuality(int a, int b, int c, const Vec2& pa) const;  // with a moved to pa

  const std::vector<BoundaryLoop>& loops_;
  const ControlSpace& cs_;
  const PlanarMesherOptions& opt_;

  // Vertex: position and cached metric Mt side by side (one cache miss, not two).
  struct Vtx {
    Vec2 p;
    SymMt m;
  };
  std::vector<Vtx> vx_;
  std::vector<int> vhint_;          // per vertex (beside vx_): the control space's location hint
  std::vector<std::uint8_t> vbnd_;  // 1: boundary or super vertex (never moved), 2: removed
  std::vector<int> vtri_;
  // Triangle: vertices (counter-clockwise), neighbours (n[i] across the edge opposite
  // v[i]) and constrained-edge bits, together in one cache line.
  struct Tri {
    std::array<int, 3> v;
    std::array<int, 3> n;
    std::uint8_t c;      // constrained-edge bits
    std::uint8_t acc;    // frontal insertion: accepted (done)
    std::uint32_t mark;  // cavity / work-list epoch
  };
  std::vector<Tri> tri_;
  std::vector<int> freeTris_;
  std::vector<std::array<int, 2>> bedges_;  // boundary edges (mesher vertex ids)
  std::vector<int> bedgeRefs_;
  int nBoundary_ = 0;

  // cavity scratch (reused)
  std::vector<std::uint32_t> forbid_, vmark_;
  std::uint32_t epoch_ = 0, fepoch_ = 0;
  std::vector<int> cav_;
  struct BndEdge {
    int a, b, outer;
    bool c;
  };
  std::vector<BndEdge> bnd_;
  std::vector<int> startAt_, endAt_, newTris_;
  // commitCavity (small cavities): start vertex -> boundary edge, slots tagged by linkTag_.
  struct LinkSlot {
    std::uint32_t tag;
    int v, k;
  };
  std::array<LinkSlot, 64> link_{};
  std::uint32_t linkTag_ = 0;
  std::uint32_t rng_ = 12345u;

  // frontal state
  std::vector<TriCache> cache_;
  bool improving_ = false;  // set by renumberSpatially: the insertion's per-triangle state is gone
  std::vector<std::uint32_t> stamp_, queued_;
  // swapSweep: per triangle, the swap clock at its last visit and at its last flip.
  struct SwapSeen {
    std::uint32_t visit, flip;
  };
  std::vector<SwapSeen> swapSeen_;
  std::uint32_t swapClock_ = 0;
  std::vector<double> tq_;  // triangle metric quality (improvement stage)
  std::vector<int> colBall_, colRing_, colBallB_;
  // tryCollapse limits; colOptimal_: a midpoint collapse puts the merged vertex at the point
  // its ring sees at unit metric length (as smoothing does) instead of the midpoint.
  double colMaxLength_ = kCollapseMaxLength, colMinQuality_ = kCollapseMinQuality;
  bool colOptimal_ = false;
  double colMinGain_ = 0.0;  // new triangles must beat the floor by this much
  bool colSearch_ = false;   // a midpoint collapse places the merged vertex by placeMergedVertex
  std::vector<std::array<int, 2>> colFan_;
  std::vector<std::uint8_t> vdirty_;  // improvement: vertex whose surroundings changed

  double estimate_ = 0.0;
  double elementRatio_ = 1.0;  // final elements per triangle
  MesherTimings timings_;

  friend struct anisomesh::BoundaryTriangulationCache;
};

inline double Mesher::triQuality(int a, int b, int c) const { return triQuality(a, b, c, vx_[a].p); }

inline double Mesher::triQuality(int a, int b, int c, const Vec2& pa) const {
  const SymMt m = SymMt::average3(vx_[a].m, vx_[b].m, vx_[c].m);
  return metricTriangleQuality(m, pa, vx_[b].p, vx_[c].p);
}

// Cavity of x: triangles reachable from t0 across unconstrained edges whose circumcircle
// (as judged by inCircle) contains x, reduced until x sees every cavity boundary edge
// strictly counter-clockwise (star-shaped, so the fan is valid). False if impossible.
template <class InCircle>
bool Mesher::buildCavity(const Vec2& x, int t0, InCircle inCircle) {
  ++fepoch_;
  for (int attempt = 0; attempt < 16; ++attempt) {
    ++epoch_;
    cav_.clear();
    cav_.push_back(t0);
    tri_[t0].mark = epoch_;
    for (size_t k = 0; k < cav_.size(); ++k) {
      const int t = cav_[k];
      for (int i = 0; i < 3; ++i) {
        if (cons(t, i)) continue;
        const int nb = tri_[t].n[i];
        if (nb < 0 || tri_[nb].mark == epoch_ || (attempt > 0 && forbid_[nb] == fepoch_)) continue;
        if (inCircle(nb)) {
          tri_[nb].mark = epoch_;
          cav_.push_back(nb);
        }
      }
    }
    bnd_.clear();
    bool ok = true;
    for (const int t : cav_) {
      for (int i = 0; i < 3; ++i) {
        const int nb = tri_[t].n[i];
        if (nb >= 0 && tri_[nb].mark == epoch_ && !cons(t, i)) continue;
        const int a = tri_[t].v[next3(i)], b = tri_[t].v[prev3(i)];
        if (orient(vx_[a].p, vx_[b].p, x) <= 0.0) {
          if (t == t0) return false;
          forbid_[t] = fepoch_;
          ok = false;
        } else {
          bnd_.push_back({a, b, nb, cons(t, i)});
        }
      }
    }
    if (!ok) continue;
    if (bnd_.size() == cav_.size() + 2) return true;  // a disc without inner vertices
    // A vertex whose whole ball is in the cavity would be lost (possible with per-triangle
    // metrics): take its triangles out of the cavity and retry.
    if (vmark_.size() < vx_.size() + 1) vmark_.resize(vx_.size() + 1024, 0);
    for (const auto& e : bnd_) vmark_[e.a] = epoch_;
    for (const int t : cav_)
      for (int i = 0; i < 3; ++i)
        if (vmark_[tri_[t].v[i]] != epoch_) {
          if (t == t0) return false;
          forbid_[t] = fepoch_;
        }
  }
  return false;
}

}  // namespace planar
}  // namespace anisomesh

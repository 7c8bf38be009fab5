// Metric Delaunay mesher of a planar domain (coordinate-transformation approach):
// exact Delaunay triangulation of the boundary points in a super-box, boundary recovery
// by edge flips, removal of outside triangles by parity flood fill, frontal-Delaunay
// insertion of inner nodes in the metric (Rebay-style point placement, Bowyer-Watson
// cavities judged by each triangle's metric circumcircle), then an adaptation loop:
// metric edge swaps, collapse of short edges (where fronts meet), split of long inner
// edges, length-bounded node smoothing, each pass on the edges that changed. Data layout is
// flat arrays of triangle records with neighbour indices; no per-insertion heap
// allocation on the hot path; the vertices are renumbered along a Hilbert curve before
// the improvement passes for cache locality.
#include "anisomesh/mesh/planar_mesher.h"

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

#include "anisomesh/core/error.h"
#include "anisomesh/mesh/predicates.h"
#include "mesh_internal.h"

namespace anisomesh {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr int kSuper = 4;                                // super-box corners are vertices 0..3
constexpr double kIdealRadius = 0.57735026918962576;     // circumradius of the unit equilateral triangle
constexpr double kAcceptRadius = 0.70710678118654752;    // triangles with metric radius below are done
constexpr int kBucketOffset = 4 * 1100;                  // bucket index offset: covers every double exponent
constexpr double kEstimateFactor = 1.0;                  // measured: within ~10% on the layer test cases
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

  Mesh run();

 private:
  // ---- setup and output ----
  void validate() const;
  void checkProgress(double fraction);
  SymMt queryMetric(const Vec2& p) const { return SymMt::from(cs_.metricAt(p).transform()); }
  Mesh output() const;

  // ---- triangle storage ----
  int allocTri();
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
  void triangulateBoundary();
  void recoverEdge(int a, int b);
  void removeOutside();
  double estimateMetricArea();
  double metricAreaRec(const Vec2& a, const Vec2& b, const Vec2& c, double da, double db, double dc, int depth,
                       std::int64_t& budget) const;
  void insertInnerNodes();
  void renumberSpatially();
  void improve();
  int swapSweep(const std::vector<int>& work, std::vector<int>& next);
  int smoothPass(std::vector<int>& touched);
  template <class EdgeOp>
  int scanEdges(const std::vector<int>* list, EdgeOp&& op);
  int lengthPass(const std::vector<int>* list, std::vector<int>& touched);
  bool tryCollapse(int a, int b, bool toMidpoint, std::vector<int>& touched);
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
  std::uint32_t rng_ = 12345u;

  // frontal state
  std::vector<TriCache> cache_;
  std::vector<std::uint32_t> stamp_, queued_;
  std::vector<double> tq_;  // triangle metric quality (improvement stage)
  std::vector<int> colBall_, colRing_, colBallB_;
  // tryCollapse limits; colOptimal_: a midpoint collapse puts the merged vertex at the point
  // its ring sees at unit metric length (as smoothing does) instead of the midpoint.
  double colMaxLength_ = kCollapseMaxLength, colMinQuality_ = kCollapseMinQuality;
  bool colOptimal_ = false;
  std::vector<std::uint8_t> vdirty_;  // improvement: vertex whose surroundings changed

  double estimate_ = 0.0;
  double elementRatio_ = 1.0;  // final elements per triangle
  MesherTimings timings_;
};

// ---------------------------------------------------------------------------------
void Mesher::validate() const {
  require(!loops_.empty(), ErrorCode::InvalidArgument, "meshPlanarBoundary: no boundary loop given");
  for (size_t l = 0; l < loops_.size(); ++l) {
    const auto& lp = loops_[l];
    const std::string name = l == 0 ? "outer loop" : "hole loop " + std::to_string(l);
    require(
        lp.points.size() >= 3, ErrorCode::InvalidArgument,
        "meshPlanarBoundary: " + name + " has " + std::to_string(lp.points.size()) + " points, at least 3 are needed");
    require(lp.edgeRefs.size() == lp.points.size(), ErrorCode::InvalidArgument,
            "meshPlanarBoundary: " + name + " has " + std::to_string(lp.points.size()) + " points but " +
                std::to_string(lp.edgeRefs.size()) + " edge refs (one per edge expected)");
    for (size_t i = 0; i < lp.points.size(); ++i)
      require(lp.points[i].allFinite(), ErrorCode::InvalidArgument,
              "meshPlanarBoundary: " + name + " point " + std::to_string(i) + " is not finite");
  }
  require(opt_.maxElements > 0, ErrorCode::InvalidArgument, "meshPlanarBoundary: maxElements must be positive");
  require(opt_.improvementPasses >= 0, ErrorCode::InvalidArgument,
          "meshPlanarBoundary: improvementPasses must be >= 0");
  require(std::isfinite(opt_.minNodeDistance) && opt_.minNodeDistance >= 0.0 && opt_.minNodeDistance < 1.0,
          ErrorCode::InvalidArgument, "meshPlanarBoundary: minNodeDistance must be in [0, 1)");
  require(std::isfinite(opt_.minQuadQuality) && opt_.minQuadQuality > 0.0 && opt_.minQuadQuality <= 1.0,
          ErrorCode::InvalidArgument, "meshPlanarBoundary: minQuadQuality must be in (0, 1]");
}

void Mesher::checkProgress(double fraction) {
  if (opt_.progress && !opt_.progress(std::min(1.0, std::max(0.0, fraction))))
    throw Error(ErrorCode::Cancelled, "meshPlanarBoundary: cancelled by the progress callback");
}

int Mesher::allocTri() {
  if (!freeTris_.empty()) {
    const int t = freeTris_.back();
    freeTris_.pop_back();
    ++stamp_[t];
    return t;
  }
  tri_.push_back(Tri{{-1, -1, -1}, {-1, -1, -1}, 0, 0, 0});
  forbid_.push_back(0);
  stamp_.push_back(0);
  queued_.push_back(std::numeric_limits<std::uint32_t>::max());
  cache_.emplace_back();
  return static_cast<int>(tri_.size()) - 1;
}

void Mesher::setNbrAcross(int tri, int a, int b, int newNbr) {
  if (tri < 0) return;
  auto& v = tri_[tri].v;
  for (int j = 0; j < 3; ++j)
    if (v[next3(j)] == b && v[prev3(j)] == a) {
      tri_[tri].n[j] = newNbr;
      return;
    }
  throw Error(ErrorCode::Internal, "meshPlanarBoundary: broken triangle adjacency");
}

int Mesher::findEdge(int a, int b, int* idx) const {
  // Rotate around a (all vertices touched here are interior to the super-box triangulation
  // or the rotation stops at a hull edge, which is then walked the other way).
  const int t0 = vtri_[a];
  int t = t0;
  for (int guard = 0; guard < 100000; ++guard) {
    const auto& v = tri_[t].v;
    const int i = v[0] == a ? 0 : (v[1] == a ? 1 : 2);
    if (v[next3(i)] == b) {
      *idx = prev3(i);
      return t;
    }
    // Next triangle counter-clockwise around a: across edge (a, v[prev]) opposite v[next].
    t = tri_[t].n[next3(i)];
    if (t < 0 || t == t0) break;
  }
  if (t < 0) {  // hit a hull edge: go clockwise from the start
    t = t0;
    for (int guard = 0; guard < 100000; ++guard) {
      const auto& v = tri_[t].v;
      const int i = v[0] == a ? 0 : (v[1] == a ? 1 : 2);
      if (v[next3(i)] == b) {
        *idx = prev3(i);
        return t;
      }
      t = tri_[t].n[prev3(i)];
      if (t < 0 || t == t0) break;
    }
  }
  return -1;
}

// Visibility walk with a deterministic pseudo-random edge order (terminates on any
// triangulation with probability one). Returns -1 when leaving the domain.
int Mesher::locate(const Vec2& x, int t, bool stopAtConstraints) {
  const int limit = 4 * static_cast<int>(tri_.size()) + 100;
  for (int steps = 0; steps < limit; ++steps) {
    rng_ = rng_ * 1664525u + 1013904223u;
    const int r = static_cast<int>((rng_ >> 16) % 3u);
    bool moved = false;
    for (int k = 0; k < 3; ++k) {
      const int i = (r + k) % 3;
      const auto& v = tri_[t].v;
      if (orient(vx_[v[next3(i)]].p, vx_[v[prev3(i)]].p, x) < 0.0) {
        if (stopAtConstraints && cons(t, i)) return -1;
        const int nb = tri_[t].n[i];
        if (nb < 0) return -1;
        t = nb;
        moved = true;
        break;
      }
    }
    if (!moved) return t;
  }
  return -1;
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

int Mesher::commitCavity(int v) {
  // Small cavities link their new triangles by a scan of the boundary list (no random
  // access into per-vertex arrays); large ones through startAt_/endAt_.
  const bool small = bnd_.size() <= 24;
  if (!small && static_cast<int>(startAt_.size()) < static_cast<int>(vx_.size())) {
    startAt_.resize(vx_.size() + 1024, -1);
    endAt_.resize(vx_.size() + 1024, -1);
  }
  newTris_.clear();
  size_t reuse = 0;
  for (size_t k = 0; k < bnd_.size(); ++k) {
    int t;
    if (reuse < cav_.size()) {
      t = cav_[reuse++];
      ++stamp_[t];
    } else {
      t = allocTri();
    }
    newTris_.push_back(t);
  }
  for (; reuse < cav_.size(); ++reuse) {  // cannot happen for a disc cavity, kept for safety
    tri_[cav_[reuse]].v = {-1, -1, -1};
    freeTris_.push_back(cav_[reuse]);
  }
  for (size_t k = 0; k < bnd_.size(); ++k) {
    const auto& e = bnd_[k];
    const int t = newTris_[k];
    tri_[t].v = {e.a, e.b, v};
    tri_[t].n[2] = e.outer;
    tri_[t].c = e.c ? 4 : 0;
    tri_[t].acc = 0;
    if (e.outer >= 0) setNbrAcross(e.outer, e.a, e.b, t);
    if (!small) {
      startAt_[e.a] = t;
      endAt_[e.b] = t;
    }
  }
  const size_t nb = bnd_.size();
  for (size_t k = 0; k < nb; ++k) {
    const int t = newTris_[k];
    if (small) {
      // Edge (b, v) borders the new triangle starting at b; edge (v, a) the one ending at a.
      const int kb = bnd_[k].b, ka = bnd_[k].a;
      int found = 0;
      for (size_t j = 0; j < nb && found != 3; ++j) {
        if (bnd_[j].a == kb) {
          tri_[t].n[0] = newTris_[j];
          found |= 1;
        }
        if (bnd_[j].b == ka) {
          tri_[t].n[1] = newTris_[j];
          found |= 2;
        }
      }
    } else {
      tri_[t].n[0] = startAt_[bnd_[k].b];
      tri_[t].n[1] = endAt_[bnd_[k].a];
    }
    vtri_[bnd_[k].a] = t;
  }
  vtri_[v] = newTris_[0];
  return newTris_[0];
}

void Mesher::flip(int t, int i) {
  const int nb = tri_[t].n[i];
  const int p = tri_[t].v[i], u = tri_[t].v[next3(i)], w = tri_[t].v[prev3(i)];
  int j = 0;
  while (tri_[nb].v[j] == u || tri_[nb].v[j] == w) ++j;
  const int q = tri_[nb].v[j];
  // t = (p, u, w), nb = (q, w, u)  ->  t = (p, u, q), nb = (q, w, p)
  const int nWP = tri_[t].n[next3(i)], nPU = tri_[t].n[prev3(i)];
  const bool cWP = cons(t, next3(i)), cPU = cons(t, prev3(i));
  // in nb = (q, w, u) at positions j, j+1, j+2: opposite w is edge (u, q), opposite u is (q, w)
  const int nUQ = tri_[nb].n[next3(j)], nQW = tri_[nb].n[prev3(j)];
  const bool cUQ = cons(nb, next3(j)), cQW = cons(nb, prev3(j));
  tri_[t].v = {p, u, q};
  tri_[t].n = {nUQ, nb, nPU};
  tri_[t].c = static_cast<std::uint8_t>((cUQ ? 1 : 0) | (cPU ? 4 : 0));
  tri_[nb].v = {q, w, p};
  tri_[nb].n = {nWP, t, nQW};
  tri_[nb].c = static_cast<std::uint8_t>((cWP ? 1 : 0) | (cQW ? 4 : 0));
  if (nUQ >= 0) setNbrAcross(nUQ, u, q, t);
  if (nWP >= 0) setNbrAcross(nWP, w, p, nb);
  ++stamp_[t];
  ++stamp_[nb];
  vtri_[p] = t;
  if (!vdirty_.empty()) vdirty_[p] = vdirty_[u] = vdirty_[q] = vdirty_[w] = 1;
  vtri_[u] = t;
  vtri_[q] = nb;
  vtri_[w] = nb;
}

// ---------------------------------------------------------------------------------
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

// Integral of det(Mt) over the domain (metric area), adaptive over the boundary triangles.
double Mesher::metricAreaRec(const Vec2& a, const Vec2& b, const Vec2& c, double da, double db, double dc, int depth,
                             std::int64_t& budget) const {
  const double area = 0.5 * std::fabs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  const Vec2 g = (a + b + c) / 3.0;
  const double dg = cs_.metricAt(g).transform().determinant();
  --budget;
  const double lo = std::min({da, db, dc, dg}), hi = std::max({da, db, dc, dg});
  if (depth >= 14 || budget <= 0 || hi <= 1.2 * lo) return area * dg;  // centroid rule
  const Vec2 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  const double dab = cs_.metricAt(ab).transform().determinant();
  const double dbc = cs_.metricAt(bc).transform().determinant();
  const double dca = cs_.metricAt(ca).transform().determinant();
  budget -= 3;
  return metricAreaRec(a, ab, ca, da, dab, dca, depth + 1, budget) +
         metricAreaRec(ab, b, bc, dab, db, dbc, depth + 1, budget) +
         metricAreaRec(ca, bc, c, dca, dbc, dc, depth + 1, budget) +
         metricAreaRec(ab, bc, ca, dab, dbc, dca, depth + 1, budget);
}

// Metric area of the domain, the larger of two estimates: adaptive quadrature over the
// boundary triangles (resolves metric features that touch the boundary) and a scanline
// sampling on a grid of up to 256 rows with even-odd coverage (sees features inside the domain that
// no boundary triangle vertex samples).
double Mesher::estimateMetricArea() {
  std::int64_t budget = 200000;
  double adaptive = 0.0;
  for (const auto& tr : tri_) {
    const auto& t = tr.v;
    const Vec2 &a = vx_[t[0]].p, &b = vx_[t[1]].p, &c = vx_[t[2]].p;
    adaptive += metricAreaRec(a, b, c, vx_[t[0]].m.det(), vx_[t[1]].m.det(), vx_[t[2]].m.det(), 0, budget);
  }
  Vec2 lo = vx_[kSuper].p, hi = lo;
  for (int v = kSuper; v < kSuper + nBoundary_; ++v) {
    lo = lo.cwiseMin(vx_[v].p);
    hi = hi.cwiseMax(vx_[v].p);
  }
  // As many rows as boundary points (64..256): the sampling stays cheap next to the mesh.
  const int kRows = std::min(256, std::max(64, nBoundary_));
  const double dy = (hi.y() - lo.y()) / kRows, dx = (hi.x() - lo.x()) / kRows;
  if (!(dx > 0.0) || !(dy > 0.0)) return adaptive;
  double grid = 0.0;
  std::vector<double> xs;
  for (int r = 0; r < kRows; ++r) {
    const double y = lo.y() + (r + 0.5) * dy;
    xs.clear();
    for (const auto& e : bedges_) {
      const Vec2 &p = vx_[e[0]].p, &q = vx_[e[1]].p;
      if ((p.y() > y) != (q.y() > y)) xs.push_back(p.x() + (y - p.y()) / (q.y() - p.y()) * (q.x() - p.x()));
    }
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {
      const double xa = xs[k], xb = xs[k + 1];
      int j = std::max(0, static_cast<int>((xa - lo.x()) / dx));
      for (; j < kRows; ++j) {
        const double c0 = std::max(xa, lo.x() + j * dx), c1 = std::min(xb, lo.x() + (j + 1) * dx);
        if (c0 >= xb) break;
        if (c1 <= c0) continue;
        grid += (c1 - c0) * dy * cs_.metricAt(Vec2(0.5 * (c0 + c1), y)).transform().determinant();
      }
    }
  }
  return std::max(adaptive, grid);
}

// ---------------------------------------------------------------------------------
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

double Mesher::triQuality(int a, int b, int c) const { return triQuality(a, b, c, vx_[a].p); }

double Mesher::triQuality(int a, int b, int c, const Vec2& pa) const {
  const SymMt m = SymMt::average3(vx_[a].m, vx_[b].m, vx_[c].m);
  return metricTriangleQuality(m, pa, vx_[b].p, vx_[c].p);
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
    const Vec2 x = mid + tc.m.solve(d * nrm);
    bool ok = d > 0.0 && x.allFinite();
    int t0 = ok ? locate(x, t, true) : -1;
    ok = t0 >= 0 && cache_[t0].r2 > 0.0;
    if (ok) {
      ok = buildCavity(x, t0, [&](int nb) {
        const TriCache& c = cache_[nb];
        return c.m.apply(x - Vec2(c.cx, c.cy)).squaredNorm() < c.r2;
      });
    }
    if (ok) {
      for (const auto& be : bnd_) {
        if (tc.m.apply(vx_[be.a].p - x).squaredNorm() < minDist2) {
          ok = false;
          break;
        }
      }
    }
    if (!ok) {
      tri_[t].acc = 1;  // give up on this triangle; its neighbours join the front
      for (int i = 0; i < 3; ++i)
        if (tri_[t].n[i] >= 0) pushIfActive(tri_[t].n[i]);
      continue;
    }
    const int v = static_cast<int>(vx_.size());
    vx_.push_back({x, queryMetric(x)});
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
           << " elements during insertion (estimate was " << static_cast<std::int64_t>(estimate_) << ")";
        throw Error(ErrorCode::ElementBudgetExceeded, os.str());
      }
      checkProgress(0.1 + 0.7 * std::min(1.0, live / std::max(1.0, estimate_)));
    }
  }
}

// ---------------------------------------------------------------------------------
// One sweep of metric-quality edge swaps over the triangles in work; flipped triangles
// go to next (they are the only ones whose edges can have become swappable).
int Mesher::swapSweep(const std::vector<int>& work, std::vector<int>& next) {
  int swaps = 0;
  for (const int t : work) {
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

// Moves every free vertex towards the point its neighbours see at unit metric distance
// (or halfway), when no triangle of its ball gets inverted and the worst one improves.
int Mesher::smoothPass(std::vector<int>& touched) {
  int moved = 0;
  std::vector<int> ring, ballTri;
  std::vector<SymMt> edgeM, triM;
  const int nv = static_cast<int>(vx_.size());
  for (int v = kSuper; v < nv; ++v) {
    if (vbnd_[v] || !vdirty_[v]) continue;  // clean: nothing around it changed since its last visit
    ring.clear();
    ballTri.clear();
    const int t0 = vtri_[v];
    int t = t0;
    for (int guard = 0; guard < 1000; ++guard) {
      const auto& tv = tri_[t].v;
      const int i = tv[0] == v ? 0 : (tv[1] == v ? 1 : 2);
      ballTri.push_back(t);
      ring.push_back(tv[next3(i)]);
      t = tri_[t].n[next3(i)];
      if (t < 0 || t == t0) break;
    }
    if (t != t0) continue;
    double before = std::numeric_limits<double>::infinity();
    for (const int bt : ballTri) before = std::min(before, tq_[bt]);
    vdirty_[v] = 0;
    if (before >= kSmoothSkipQuality) continue;  // already good: not worth the metric queries
    const Vec2 p = vx_[v].p;
    const size_t deg = ring.size();
    // Metrics of the ring edges and ball triangles (the vertex keeps its metric while the
    // candidates are judged): computed once, used for every candidate.
    edgeM.resize(deg);
    triM.resize(deg);
    for (size_t k = 0; k < deg; ++k) {
      edgeM[k] = SymMt::average2(vx_[v].m, vx_[ring[k]].m);
      triM[k] = SymMt::average3(vx_[v].m, vx_[ring[k]].m, vx_[ring[k + 1 == deg ? 0 : k + 1]].m);
    }
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
    vx_[v].m = queryMetric(cands[best]);
    for (size_t k = 0; k < ballTri.size(); ++k) touched.push_back(ballTri[k]);
    ++moved;
  }
  return moved;
}

// Hilbert index of (x, y) in [0, 2^16)^2 (for cache-friendly renumbering).
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t n = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1u : 0u, ry = (y & s) ? 1u : 0u;
    d += static_cast<std::uint64_t>(s) * s * ((3u * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

// Renumbers the inner vertices along a Hilbert curve and the triangles by their first
// vertex, dropping free slots: the frontal insertion creates them in order of size, not
// of position, and the later passes walk around vertices (cache misses dominate otherwise).
void Mesher::renumberSpatially() {
  const int nv = static_cast<int>(vx_.size());
  const int first = kSuper + nBoundary_;
  Vec2 lo = vx_[kSuper].p, hi = lo;
  for (int v = kSuper; v < nv; ++v) {
    lo = lo.cwiseMin(vx_[v].p);
    hi = hi.cwiseMax(vx_[v].p);
  }
  const Vec2 ext = (hi - lo).cwiseMax(Vec2(1e-300, 1e-300));
  // Hilbert keys (< 2^32) sorted by a stable two-digit radix sort: ties keep the vertex order.
  const int n = nv - first;
  std::vector<std::uint32_t> key(n);
  for (int v = first; v < nv; ++v) {
    const Vec2 f = (vx_[v].p - lo).cwiseQuotient(ext) * 65535.0;
    key[v - first] =
        static_cast<std::uint32_t>(hilbertIndex(static_cast<std::uint32_t>(f.x()), static_cast<std::uint32_t>(f.y())));
  }
  std::vector<int> order(n), tmp(n);
  for (int k = 0; k < n; ++k) tmp[k] = k;
  for (int shift = 0; shift < 32; shift += 16) {
    std::vector<int> cnt((1 << 16) + 1, 0);
    for (int k = 0; k < n; ++k) ++cnt[((key[tmp[k]] >> shift) & 0xffffu) + 1];
    for (int d = 0; d < (1 << 16); ++d) cnt[d + 1] += cnt[d];
    for (int k = 0; k < n; ++k) order[cnt[(key[tmp[k]] >> shift) & 0xffffu]++] = tmp[k];
    order.swap(tmp);
  }
  std::vector<int> vmap(nv);
  for (int v = 0; v < first; ++v) vmap[v] = v;
  for (int k = 0; k < n; ++k) vmap[first + tmp[k]] = first + k;
  {
    std::vector<Vtx> x(nv);
    std::vector<std::uint8_t> b(nv);
    for (int v = 0; v < nv; ++v) {
      x[vmap[v]] = vx_[v];
      b[vmap[v]] = vbnd_[v];
    }
    vx_.swap(x);
    vbnd_.swap(b);
  }
  // Triangles: counting sort by their smallest new vertex index (stable, linear).
  const int nt = static_cast<int>(tri_.size());
  std::vector<int> count(nv + 1, 0);
  for (int t = 0; t < nt; ++t) {
    if (tri_[t].v[0] < 0) continue;
    for (int i = 0; i < 3; ++i) tri_[t].v[i] = vmap[tri_[t].v[i]];
    ++count[std::min({tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]}) + 1];
  }
  for (int v = 0; v < nv; ++v) count[v + 1] += count[v];
  const int live = count[nv];
  std::vector<int> tmap(nt, -1);
  for (int t = 0; t < nt; ++t)
    if (tri_[t].v[0] >= 0) tmap[t] = count[std::min({tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]})]++;
  std::vector<Tri> tris(live);
  for (int t = 0; t < nt; ++t) {
    const int k = tmap[t];
    if (k < 0) continue;
    tris[k] = tri_[t];
    tris[k].acc = 0;
    tris[k].mark = 0;
    for (int i = 0; i < 3; ++i) tris[k].n[i] = tri_[t].n[i] >= 0 ? tmap[tri_[t].n[i]] : -1;
  }
  tri_.swap(tris);
  freeTris_.clear();
  forbid_.assign(live, 0);
  stamp_.assign(live, 0);
  queued_.assign(live, 0);
  cache_.clear();
  cache_.shrink_to_fit();
  vtri_.assign(nv, -1);
  for (int t = 0; t < live; ++t)
    for (int i = 0; i < 3; ++i) vtri_[tri_[t].v[i]] = t;
}

// Collapses inner vertex a onto its neighbour b (edge a-b too short), b staying or, with
// toMidpoint (b inner too), moving to the edge's midpoint: the two triangles of the edge
// disappear, the rest of a's ball is re-attached to b. Refused when the link condition
// fails (would create a duplicate edge), when a triangle would turn or become poor, or
// when a new edge would be too long.
bool Mesher::tryCollapse(int a, int b, bool toMidpoint, std::vector<int>& touched) {
  if (vbnd_[a]) return false;
  std::vector<int>& ball = colBall_;
  std::vector<int>& ring = colRing_;
  ball.clear();
  ring.clear();
  const int t0 = vtri_[a];
  int t = t0;
  for (int guard = 0; guard < 1000; ++guard) {
    const auto& tv = tri_[t].v;
    const int i = tv[0] == a ? 0 : (tv[1] == a ? 1 : 2);
    ball.push_back(t);
    ring.push_back(tv[next3(i)]);
    t = tri_[t].n[next3(i)];
    if (t < 0 || t == t0) break;
  }
  if (t != t0) return false;
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
  if (toMidpoint) {
    pb = 0.5 * (vx_[a].p + vx_[b].p);
    mb = queryMetric(pb);
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
      mb = queryMetric(pb);
    }
  }
  const double floor = std::min(before, colMinQuality_);
  for (int k = 0; k < deg; ++k) {
    const int r = ring[k];
    if (r != b && tooLong(r)) return false;
    if (k == k1 || k == k2) continue;
    const int c = ring[(k + 1) % deg];
    if (orient(pb, vx_[r].p, vx_[c].p) <= 0.0) return false;
    if (quality(r, c) < floor) return false;
  }
  for (const int u : ballB) {
    const auto& tv = tri_[u].v;
    const int i = tv[0] == b ? 0 : (tv[1] == b ? 1 : 2);
    const int r = tv[next3(i)], c = tv[prev3(i)];
    if (tooLong(r)) return false;
    if (orient(pb, vx_[r].p, vx_[c].p) <= 0.0) return false;
    if (quality(r, c) < floor) return false;
  }
  // Apply.
  vx_[b].p = pb;
  vx_[b].m = mb;
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
  vx_.push_back({x, queryMetric(x)});
  const double floor = std::min(kSplitMinQuality, std::min(tq_[t], tq_[nb]));
  const double q1 = triQuality(p, u, v), q2 = triQuality(p, v, w), q3 = triQuality(q, w, v), q4 = triQuality(q, v, u);
  if (!(std::min({q1, q2, q3, q4}) >= floor)) {
    vx_.pop_back();
    return false;
  }
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

// Collapses edges shorter than kCollapseLength (fronts meeting leave some), removing an
// inner end point (onto the midpoint when both ends are inner, else onto the other end),
// and splits inner edges longer than kSplitLength (new edges wait for the next pass).
// Scans every triangle, or only those in list (whose edges changed since the last scan).
int Mesher::lengthPass(const std::vector<int>* list, std::vector<int>& touched) {
  return scanEdges(list, [&](int t, int i, int u, int w) {
    const double len = SymMt::average2(vx_[u].m, vx_[w].m).length(vx_[w].p - vx_[u].p);
    if (len < kCollapseLength) {
      const bool inner = !vbnd_[u] && !vbnd_[w];
      return (inner && tryCollapse(u, w, true, touched)) || tryCollapse(u, w, false, touched) ||
             tryCollapse(w, u, false, touched);
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
    const bool inner = !vbnd_[u] && !vbnd_[w];
    bool done = false;
    if (inner) {
      colOptimal_ = true;
      done = tryCollapse(u, w, true, touched);
      colOptimal_ = false;
    }
    return done || (inner && tryCollapse(u, w, true, touched)) || tryCollapse(u, w, false, touched) ||
           tryCollapse(w, u, false, touched);
  });
  colMaxLength_ = kCollapseMaxLength;
  colMinQuality_ = kCollapseMinQuality;
  return changed;
}

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
  auto swaps = [&](int sweeps) {
    for (int k = 0; k < sweeps && !work.empty(); ++k) {
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
    swaps(6);
    work.clear();
    const std::vector<int>* list = pass == 0 ? nullptr : &scan;
    const int resized = lengthPass(list, work);
    dedupe(work);
    changed.insert(changed.end(), work.begin(), work.end());
    swaps(6);
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
  if (opt_.improvementPasses > 0) swaps(6);
  // Final short-edge rounds, each followed by swaps and a smoothing of the changed balls;
  // the first round scans every edge, the next ones the edges that changed.
  for (int round = 0; round < kFinalCollapseRounds && opt_.improvementPasses > 0; ++round) {
    work.clear();
    changed.clear();
    const int collapsed = shortEdgePass(round == 0 ? nullptr : &scan, work);
    if (collapsed == 0) break;
    dedupe(work);
    changed.insert(changed.end(), work.begin(), work.end());
    swaps(6);
    work.clear();
    smoothPass(work);
    dedupe(work);
    for (const int t : work) tq_[t] = triQuality(tri_[t].v[0], tri_[t].v[1], tri_[t].v[2]);
    changed.insert(changed.end(), work.begin(), work.end());
    swaps(6);
    scan.swap(changed);
    dedupe(scan);
  }
}

// ---------------------------------------------------------------------------------
Mesh Mesher::output() const {
  Mesh m;
  m.dimension = 2;
  // Removed (collapsed) vertices are skipped; boundary vertices keep their places first.
  std::vector<int> vmap(vx_.size(), -1);
  int nv = 0;
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v)
    if (vbnd_[v] != 2) vmap[v] = nv++;
  m.points.reserve(nv);
  m.params.reserve(nv);
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v) {
    if (vmap[v] < 0) continue;
    m.points.emplace_back(vx_[v].p.x(), vx_[v].p.y(), 0.0);
    m.params.push_back(vx_[v].p);
  }
  m.pointRefs.assign(nv, 0);
  for (size_t e = 0; e < bedges_.size(); ++e) {
    m.edges.push_back({vmap[bedges_[e][0]], vmap[bedges_[e][1]]});
    m.edgeRefs.push_back(bedgeRefs_[e]);
  }
  m.triangles.reserve(tri_.size());
  for (const auto& tr : tri_) {
    const auto& t = tr.v;
    if (t[0] < 0) continue;
    m.triangles.push_back({vmap[t[0]], vmap[t[1]], vmap[t[2]]});
  }
  m.triangleRefs.assign(m.triangles.size(), 0);
  return m;
}

Mesh Mesher::run() {
  validate();
  auto t0 = Clock::now();
  elementRatio_ = opt_.allQuads ? 2.0 : (opt_.quads ? 0.6 : 1.0);
  checkProgress(0.0);
  triangulateBoundary();
  removeOutside();
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v) vx_[v].m = queryMetric(vx_[v].p);

  Mesh mesh;
  if (opt_.boundaryOnly) {
    timings_.boundary = secondsSince(t0);
    mesh = output();
  } else {
    // Budget check before the expensive work: one unit equilateral triangle per sqrt(3)/4 of metric area.
    const double metricArea = estimateMetricArea();
    timings_.boundary = secondsSince(t0);
    estimate_ = std::max(static_cast<double>(liveTriangles()), kEstimateFactor * metricArea / (std::sqrt(3.0) / 4.0));
    timings_.estimatedElements = static_cast<std::int64_t>(estimate_ * elementRatio_);
    if (estimate_ * elementRatio_ > static_cast<double>(opt_.maxElements)) {
      std::ostringstream os;
      os << "meshPlanarBoundary: the requested mesh needs about " << timings_.estimatedElements
         << " elements, above the element budget of " << opt_.maxElements;
      throw Error(ErrorCode::ElementBudgetExceeded, os.str());
    }
    checkProgress(0.1);
    t0 = Clock::now();
    // Room for the expected mesh (the estimate is within ~10%): no reallocation copies.
    const size_t expect = static_cast<size_t>(std::min(1.15 * estimate_, static_cast<double>(opt_.maxElements))) + 1024;
    tri_.reserve(expect);
    forbid_.reserve(expect);
    stamp_.reserve(expect);
    queued_.reserve(expect);
    cache_.reserve(expect);
    vx_.reserve(expect / 2 + nBoundary_);
    vbnd_.reserve(expect / 2 + nBoundary_);
    vtri_.reserve(expect / 2 + nBoundary_);
    insertInnerNodes();
    timings_.insertion = secondsSince(t0);
    t0 = Clock::now();
    renumberSpatially();
    improve();
    timings_.improvement = secondsSince(t0);
    mesh = output();
    if (opt_.quads || opt_.allQuads) {
      t0 = Clock::now();
      std::vector<SymMt> vm;
      vm.reserve(vx_.size() - kSuper);
      for (size_t v = kSuper; v < vx_.size(); ++v)
        if (vbnd_[v] != 2) vm.push_back(vx_[v].m);
      convertToQuads(mesh, vm, opt_.allQuads, opt_.minQuadQuality);
      timings_.quads = secondsSince(t0);
    }
  }
  if (mesh.elementCount() > opt_.maxElements) {
    std::ostringstream os;
    os << "meshPlanarBoundary: the mesh has " << mesh.elementCount() << " elements, above the element budget of "
       << opt_.maxElements;
    throw Error(ErrorCode::ElementBudgetExceeded, os.str());
  }
  checkProgress(1.0);
  if (opt_.timings) *opt_.timings = timings_;
  return mesh;
}

}  // namespace

Mesh meshPlanarBoundary(const std::vector<BoundaryLoop>& loops, const ControlSpace& controlSpace,
                        const PlanarMesherOptions& options) {
  Mesher mesher(loops, controlSpace, options);
  return mesher.run();
}

}  // namespace anisomesh

#include "anisomesh/controlspace/background_mesh_control_space.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "judge_in_slices.h"
#include "spatial_order.h"

namespace anisomesh {

BackgroundMeshControlSpace::BackgroundMeshControlSpace(const Box2& box, const BackgroundMeshOptions& options)
    : options_(options) {
  require(box.lo.allFinite() && box.hi.allFinite() && box.hi.x() > box.lo.x() && box.hi.y() > box.lo.y(),
          ErrorCode::InvalidDomain, "background mesh control space needs a finite box with lo < hi in both axes");
  require(options.initialGrid >= 1 && options.initialGrid <= 1024, ErrorCode::InvalidArgument,
          "background mesh initialGrid must be in [1, 1024], got " + std::to_string(options.initialGrid));
  require(options.maxLevel >= 0 && options.maxLevel <= 40, ErrorCode::InvalidArgument,
          "background mesh maxLevel must be in [0, 40], got " + std::to_string(options.maxLevel));
  require(std::isfinite(options.epsilon) && options.epsilon >= 0.0, ErrorCode::InvalidArgument,
          "background mesh epsilon must be finite and >= 0");
  box_ = box;
  const int n = options.initialGrid;
  const Vec2 sz = box.size();
  minSize_ = (sz / n).norm() / std::ldexp(1.0, options.maxLevel);
  const double eps = options.epsilon * sz.norm();
  eps2_ = eps * eps;
  // 1e-9 of a triangle's size: far above the rounding of orient() (~1e-16 of it) in this
  // triangle or in any neighbour (bisection keeps their sizes within a small factor).
  margin2_ = 1e-18;
  const Metric placeholder = options.initialMetric ? *options.initialMetric : Metric::isotropic(sz.norm());
  const SymMt pm = toSymMt(placeholder);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Vec2 p(i == n ? box.hi.x() : box.lo.x() + sz.x() * i / n,
                   j == n ? box.hi.y() : box.lo.y() + sz.y() * j / n);
      addNode(p, pm, options.initialMetric.has_value());
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v00 = j * (n + 1) + i, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
      tri_.push_back({v00, v10, v11});
      tri_.push_back({v00, v11, v01});
    }
  // Neighbours by matching edges.
  std::vector<std::tuple<int, int, int, int>> edges;  // (min, max, tri, k)
  for (int t = 0; t < static_cast<int>(tri_.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tri_[t][(k + 1) % 3], b = tri_[t][(k + 2) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b), t, k);
    }
  std::sort(edges.begin(), edges.end());
  nbr_.assign(tri_.size(), {-1, -1, -1});
  for (size_t e = 0; e + 1 < edges.size(); ++e) {
    const auto& [a0, b0, t0, k0] = edges[e];
    const auto& [a1, b1, t1, k1] = edges[e + 1];
    if (a0 == a1 && b0 == b1) {
      nbr_[t0][k0] = t1;
      nbr_[t1][k1] = t0;
    }
  }
  rebuildLocator();
}

Vec2 BackgroundMeshControlSpace::clampedToBox(const Vec2& p) const {
  return p.allFinite() ? Vec2(p.cwiseMax(box_.lo).cwiseMin(box_.hi)) : box_.lo;
}

double BackgroundMeshControlSpace::orient(int a, int b, const Vec2& p) const {
  const Vec2& pa = pos_[a];
  const Vec2& pb = pos_[b];
  return (pb.x() - pa.x()) * (p.y() - pa.y()) - (pb.y() - pa.y()) * (p.x() - pa.x());
}

double BackgroundMeshControlSpace::edgeKey(int a, int b) const {
  // Canonical order so both triangles sharing the edge compute the same bits.
  if (a > b) std::swap(a, b);
  return (pos_[b] - pos_[a]).squaredNorm();
}

int BackgroundMeshControlSpace::longestEdge(int t) const {
  // Total order on edges: length, then vertex ids (LEPP needs consistent choices).
  int best = 0;
  auto key = [&](int k) {
    const int a = tri_[t][(k + 1) % 3], b = tri_[t][(k + 2) % 3];
    return std::make_tuple(edgeKey(a, b), std::min(a, b), std::max(a, b));
  };
  auto bk = key(0);
  for (int k = 1; k < 3; ++k) {
    const auto kk = key(k);
    if (kk > bk) {
      bk = kk;
      best = k;
    }
  }
  return best;
}

void BackgroundMeshControlSpace::splitPair(int t, int i) {
  auto touch = [&](int x) {
    if (x >= static_cast<int>(touchedFlag_.size())) touchedFlag_.resize(x + 1, 0);
    if (!touchedFlag_[x]) {
      touchedFlag_[x] = 1;
      touched_.push_back(x);
    }
  };
  const int a = tri_[t][i], b = tri_[t][(i + 1) % 3], c = tri_[t][(i + 2) % 3];
  const int n = nbr_[t][i];
  const int tAB = nbr_[t][(i + 2) % 3], tCA = nbr_[t][(i + 1) % 3];
  const SymMt& mb = mt_[b];
  const SymMt& mc = mt_[c];
  const SymMt mm{0.5 * (mb.a + mc.a), 0.5 * (mb.b + mc.b), 0.5 * (mb.c + mc.c)};
  const bool init = nodeIsInitialized(b) && nodeIsInitialized(c);
  const int m = addNode(0.5 * (pos_[b] + pos_[c]), mm, init);
  const int t2 = static_cast<int>(tri_.size());
  const int n2 = n >= 0 ? t2 + 1 : -1;
  tri_.push_back({a, m, c});
  nbr_.push_back({n, tCA, t});
  tri_[t] = {a, b, m};
  nbr_[t] = {n2, t2, tAB};
  if (tCA >= 0)
    for (int& x : nbr_[tCA])
      if (x == t) x = t2;
  touch(t);
  touch(t2);
  if (n >= 0) {
    int j = 0;
    while (nbr_[n][j] != t) ++j;
    const int d = tri_[n][j];
    const int nDC = nbr_[n][(j + 2) % 3], nBD = nbr_[n][(j + 1) % 3];
    tri_.push_back({d, m, b});
    nbr_.push_back({t, nBD, n});
    tri_[n] = {d, c, m};
    nbr_[n] = {t2, n2, nDC};
    if (nBD >= 0)
      for (int& x : nbr_[nBD])
        if (x == n) x = n2;
    touch(n);
    touch(n2);
  }
}

void BackgroundMeshControlSpace::bisect(int t) {
  require(t >= 0 && t < elementCount(), ErrorCode::InvalidArgument, "bisect: no such triangle");
  bisectImpl(t);
  touched_.clear();
  touchedFlag_.clear();
  rebuildLocator();
}

void BackgroundMeshControlSpace::bisectImpl(int t) {
  // Longest-edge propagation path: refine the neighbour until the edge is longest for both.
  std::vector<int> path{t};
  while (!path.empty()) {
    const int u = path.back();
    const int i = longestEdge(u);
    const int n = nbr_[u][i];
    if (n < 0) {
      splitPair(u, i);
      path.pop_back();
      continue;
    }
    int j = 0;
    while (nbr_[n][j] != u) ++j;
    if (longestEdge(n) == j) {
      splitPair(u, i);
      path.pop_back();
    } else {
      path.push_back(n);
    }
  }
}

void BackgroundMeshControlSpace::rebuildLocator() {
  locatorStale_ = false;
  const double nt = static_cast<double>(tri_.size());
  gridSide_ = std::clamp(static_cast<int>(std::sqrt(nt / 2.0)), 1, 2048);
  const Vec2 sz = box_.size();
  gridInv_ = Vec2(gridSide_ / sz.x(), gridSide_ / sz.y());
  grid_.assign(static_cast<size_t>(gridSide_) * gridSide_, 0);
  int t = 0;
  for (int j = 0; j < gridSide_; ++j) {
    // Serpentine order keeps consecutive centres close (short walks).
    for (int ii = 0; ii < gridSide_; ++ii) {
      const int i = (j & 1) ? gridSide_ - 1 - ii : ii;
      const Vec2 q(box_.lo.x() + (i + 0.5) * sz.x() / gridSide_, box_.lo.y() + (j + 0.5) * sz.y() / gridSide_);
      const size_t cell = static_cast<size_t>(j) * gridSide_ + i;
      grid_[cell] = t;  // start the walk from the previous centre's triangle
      t = locateTriangle(q);
      grid_[cell] = t;
    }
  }
}

bool BackgroundMeshControlSpace::triangleContains(int t, const Vec2& p) const {
  const auto& v = tri_[t];
  const double scale = 1e-12 * box_.size().squaredNorm();
  return orient(v[1], v[2], p) >= -scale && orient(v[2], v[0], p) >= -scale && orient(v[0], v[1], p) >= -scale;
}

int BackgroundMeshControlSpace::locateTriangle(const Vec2& p) const {
  // Stale only inside refine() (exclusive access): the first query of a batch rebuilds
  // the grid exactly as an eager rebuild after the batch would have.
  if (locatorStale_) const_cast<BackgroundMeshControlSpace*>(this)->rebuildLocator();
  const Vec2 q = clampedToBox(p);
  const int gi = std::clamp(static_cast<int>((q.x() - box_.lo.x()) * gridInv_.x()), 0, gridSide_ - 1);
  const int gj = std::clamp(static_cast<int>((q.y() - box_.lo.y()) * gridInv_.y()), 0, gridSide_ - 1);
  int t = grid_[static_cast<size_t>(gj) * gridSide_ + gi];
  const int cap = 64 + 4 * gridSide_;
  // (k + 1) % 3 and (k + 2) % 3 without the divisions: this walk is the hot part of a query.
  constexpr int kNext[3] = {1, 2, 0}, kPrev[3] = {2, 0, 1};
  int first = 0;  // step % 3
  for (int step = 0; step < cap; ++step, first = kNext[first]) {
    const auto& v = tri_[t];
    int next = -1;
    // Rotating the first edge tested avoids the (rare) cycles of visibility walks.
    for (int r = 0, k = first; r < 3; ++r, k = kNext[k]) {
      if (orient(v[kNext[k]], v[kPrev[k]], q) < 0.0) {
        next = nbr_[t][k];
        if (next >= 0) break;
      }
    }
    if (next < 0) return t;
    t = next;
  }
  // Fallback: exhaustive search (never seen on bisection meshes, kept for robustness).
  for (int u = 0; u < elementCount(); ++u)
    if (triangleContains(u, q)) return u;
  return t;
}

int BackgroundMeshControlSpace::locateTriangleFrom(const Vec2& q, int from, double* o) const {
  if (locatorStale_ || from < 0 || from >= elementCount()) return -1;
  // A query next to the previous one: 60 % of the mesher's fall in the same background
  // triangle or a neighbour; farther ones are left to the grid (a longer walk costs more).
  // Up to five moves: with the mesher's per-vertex hints, 1e5 remesh (boundary case), 6 %
  // of the queries need 3 to 5 moves and 14 % more (those take the grid).
  int t = from;
  for (int step = 0; step < 6; ++step) {
    const auto& v = tri_[t];
    // The first edge (in order) that q is beyond and that has a neighbour is crossed: the
    // edges after it need no test.
    o[0] = orient(v[1], v[2], q);
    if (o[0] < 0.0 && nbr_[t][0] >= 0) {
      t = nbr_[t][0];
      continue;
    }
    o[1] = orient(v[2], v[0], q);
    if (o[1] < 0.0 && nbr_[t][1] >= 0) {
      t = nbr_[t][1];
      continue;
    }
    o[2] = orient(v[0], v[1], q);
    if (o[2] < 0.0 && nbr_[t][2] >= 0) {
      t = nbr_[t][2];
      continue;
    }
    if (o[0] > 0.0 && o[1] > 0.0 && o[2] > 0.0) {
      // Clearly inside (each edge's line at least 1e-9 of the triangle's size away): the
      // only triangle any walk can stop in, so locateTriangle's answer too.
      const double l0 = (pos_[v[2]] - pos_[v[1]]).squaredNorm(), l1 = (pos_[v[0]] - pos_[v[2]]).squaredNorm(),
                   l2 = (pos_[v[1]] - pos_[v[0]]).squaredNorm();
      const double m = margin2_ * (l0 + l1 + l2);
      return o[0] * o[0] > m * l0 && o[1] * o[1] > m * l1 && o[2] * o[2] > m * l2 ? t : -1;
    }
    return -1;  // on an edge's line, or beyond the box's edges only
  }
  return -1;
}

Metric BackgroundMeshControlSpace::metricAtNear(const Vec2& p, int& hint) const {
  const Vec2 q = clampedToBox(p);
  double o[3];
  const int t = locateTriangleFrom(q, hint, o);
  if (t < 0) {
    hint = locateTriangle(q);
    return toMetric(mtIn(hint, q));
  }
  hint = t;
  // Linear weights: mtIn's orient() values, computed above (all positive).
  return toMetric(options_.interpolation == BackgroundInterpolation::Linear ? weighted(t, o) : mtIn(t, q));
}

SymMt BackgroundMeshControlSpace::mtAt(const Vec2& p) const {
  const Vec2 q = clampedToBox(p);
  return mtIn(locateTriangle(q), q);
}

Metric BackgroundMeshControlSpace::elementSampleMetric(const ControlElement& e, int k) const {
  const Vec2& p = e.samples[size_t(k)];
  if (options_.interpolation != BackgroundInterpolation::Linear || e.id < 0 || e.id >= elementCount())
    return metricAt(p);
  const Vec2 q = clampedToBox(p);
  return toMetric(mtIn(e.id, q));
}

SymMt BackgroundMeshControlSpace::mtIn(int t, const Vec2& q) const {
  const auto& v = tri_[t];
  double w[3];
  if (options_.interpolation == BackgroundInterpolation::Linear) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
      w[k] = std::max(orient(v[(k + 1) % 3], v[(k + 2) % 3], q), 0.0);
      s += w[k];
    }
    if (s <= 0.0) {
      w[0] = w[1] = w[2] = 1.0;
    }
  } else {
    for (int k = 0; k < 3; ++k) {
      const double d2 = (q - pos_[v[k]]).squaredNorm();
      if (d2 <= eps2_) return mt_[v[k]];
      w[k] = 1.0 / d2;
    }
  }
  return weighted(t, w);
}

SymMt BackgroundMeshControlSpace::weighted(int t, const double* w) const {
  const auto& v = tri_[t];
  const double inv = 1.0 / (w[0] + w[1] + w[2]);
  SymMt r{0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const SymMt& m = mt_[v[k]];
    r.a += w[k] * m.a;
    r.b += w[k] * m.b;
    r.c += w[k] * m.c;
  }
  r.a *= inv;
  r.b *= inv;
  r.c *= inv;
  return r;
}

InterpolationStencil BackgroundMeshControlSpace::stencilAt(const Vec2& p) const {
  const Vec2 q = clampedToBox(p);
  const auto& v = tri_[locateTriangle(q)];
  InterpolationStencil s;
  s.count = 3;
  for (int k = 0; k < 3; ++k) s.nodes[size_t(k)] = v[k];
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    double w;
    if (options_.interpolation == BackgroundInterpolation::Linear) {
      w = std::max(orient(v[(k + 1) % 3], v[(k + 2) % 3], q), 0.0);
    } else {
      const double d2 = (q - pos_[v[k]]).squaredNorm();
      if (d2 <= eps2_) {  // at a vertex: its value (eq. 11's epsilon shortcut)
        s.count = 1;
        s.nodes[0] = v[k];
        s.weights[0] = 1.0;
        return s;
      }
      w = 1.0 / d2;
    }
    s.weights[size_t(k)] = w;
    sum += w;
  }
  for (int k = 0; k < 3; ++k) s.weights[size_t(k)] = sum > 0.0 ? s.weights[size_t(k)] / sum : 1.0 / 3.0;
  return s;
}

Metric BackgroundMeshControlSpace::metricAt(const Vec2& p) const { return toMetric(mtAt(p)); }

std::vector<std::array<int, 2>> BackgroundMeshControlSpace::rawEdges(bool /*structure*/) const {
  std::vector<std::array<int, 2>> edges;
  edges.reserve(tri_.size() * 3 / 2 + 8);
  for (int t = 0; t < elementCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int n = nbr_[t][k];
      if (n >= 0 && n < t) continue;
      const int a = tri_[t][(k + 1) % 3], b = tri_[t][(k + 2) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  return edges;
}

std::vector<std::vector<int>> BackgroundMeshControlSpace::elementNodes() const {
  std::vector<std::vector<int>> out;
  out.reserve(tri_.size());
  for (const auto& t : tri_) out.push_back({t[0], t[1], t[2]});
  return out;
}

ControlElement BackgroundMeshControlSpace::elementOf(int t) const {
  ControlElement e;
  e.id = t;
  const auto& v = tri_[t];
  const Vec2 &a = pos_[v[0]], &b = pos_[v[1]], &c = pos_[v[2]];
  e.box.lo = a.cwiseMin(b).cwiseMin(c);
  e.box.hi = a.cwiseMax(b).cwiseMax(c);
  e.size = std::sqrt(std::max({(a - b).squaredNorm(), (b - c).squaredNorm(), (c - a).squaredNorm()}));
  e.nodeCount = 3;
  for (int k = 0; k < 3; ++k) e.nodes[k] = v[k];
  e.sampleCount = 4;
  e.samples[0] = (a + b + c) / 3.0;
  e.samples[1] = 0.5 * (a + b);
  e.samples[2] = 0.5 * (b + c);
  e.samples[3] = 0.5 * (c + a);
  return e;
}

void BackgroundMeshControlSpace::refine(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) {
  refineImpl(pred, onNewNodes, false);
}

void BackgroundMeshControlSpace::refineConcurrently(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) {
  refineImpl(pred, onNewNodes, true);
}

// readOnly: pred only reads (refineConcurrently), so the elements of a round may be judged
// in any order and in parallel; otherwise in element order on this thread.
void BackgroundMeshControlSpace::refineImpl(const ElementPredicate& pred, const NewNodesCallback& onNewNodes,
                                            bool readOnly) {
  std::vector<int> work(tri_.size());
  for (size_t t = 0; t < work.size(); ++t) work[t] = static_cast<int>(t);
  std::vector<int> split;
  std::vector<std::uint8_t> verdict;
  const double min2 = minSize_ * minSize_;
  auto wanted = [&](int t) {
    const auto& v = tri_[t];
    const double l2 = std::max({edgeKey(v[0], v[1]), edgeKey(v[1], v[2]), edgeKey(v[2], v[0])});
    return l2 > min2 && pred(elementOf(t));
  };
  std::vector<Vec2> centroids;
  while (!work.empty()) {
    split.clear();
    if (readOnly) {
      // Concurrent queries of pred must not rebuild the locator under each other's feet
      // (on one thread, the first query rebuilds it, if any: a predicate that queries no
      // point, as the continuous insertion's, never pays for it).
      if (locatorStale_ && threadCount() > 1) rebuildLocator();
      // Judged in the Z-order of the elements' centroids: neighbours query the same data
      // one after another (a carrier mesh's triangles stay in cache instead of being
      // fetched from memory again for each; the element order jumps across the domain).
      // Slices of that order in parallel chunks (verdicts stored per element), the
      // progress ticks on this thread; the split list in element order, as refine() makes it.
      centroids.resize(work.size());
      for (size_t k = 0; k < work.size(); ++k) {
        const auto& v = tri_[size_t(work[k])];
        centroids[k] = (pos_[v[0]] + pos_[v[1]] + pos_[v[2]]) / 3.0;
      }
      const std::vector<int> order = controlspace_internal::zOrder(centroids);
      // (on one thread, short slices: the progress ticks, which may cancel, come every few ms)
      verdict.resize(work.size());
      controlspace_internal::judgeInSlices(
          work.size(), threadCount() > 1 ? 16384 : 1024, 512,
          [&](size_t k) {
            const size_t at = size_t(order[k]);
            verdict[at] = wanted(work[at]) ? 1 : 0;
          },
          [&] { refinementTick(); });
      for (size_t k = 0; k < work.size(); ++k)
        if (verdict[k]) split.push_back(work[k]);
    } else {
      for (int t : work) {
        refinementTick();
        if (wanted(t)) split.push_back(t);
      }
    }
    if (split.empty()) break;
    // A bisection adds one node on the longest edge, about two with its conforming neighbour.
    checkRefinementEstimate(std::int64_t(split.size()), 1.0);
    const int nodesBefore = nodeCount();
    touched_.clear();
    touchedFlag_.assign(tri_.size(), 0);
    for (int t : split) {
      refinementTick();
      if (!touchedFlag_[t]) bisectImpl(t);  // a touched triangle is already a child: re-checked next batch
    }
    checkRefinementEstimate(0, 0.0);
    locatorStale_ = true;  // rebuilt by the next query, or at the end
    if (onNewNodes) onNewNodes(nodesBefore, nodeCount());
    // The touched triangles in increasing order: read off their flags when they are many
    // (a pass over the flags costs less than sorting them), sorted when they are few.
    if (touched_.size() * 16 > touchedFlag_.size()) {
      work.clear();
      for (size_t t = 0; t < touchedFlag_.size(); ++t)
        if (touchedFlag_[t]) work.push_back(static_cast<int>(t));
    } else {
      work = touched_;
      std::sort(work.begin(), work.end());
    }
  }
  touched_.clear();
  touchedFlag_.clear();
  if (locatorStale_) rebuildLocator();
}

std::vector<double> BackgroundMeshControlSpace::nodeElementSizes() const {
  std::vector<double> out(nodeCount(), std::numeric_limits<double>::infinity());
  for (const auto& v : tri_) {
    const double l = std::sqrt(std::max({edgeKey(v[0], v[1]), edgeKey(v[1], v[2]), edgeKey(v[2], v[0])}));
    for (int k = 0; k < 3; ++k) out[v[k]] = std::min(out[v[k]], l);
  }
  return out;
}

size_t BackgroundMeshControlSpace::memoryBytes() const {
  return tri_.capacity() * sizeof(tri_[0]) + nbr_.capacity() * sizeof(nbr_[0]) + grid_.capacity() * 4 +
         pos_.capacity() * sizeof(Vec2) + mt_.capacity() * sizeof(SymMt) + flags_.capacity() + edgeGraphBytes();
}

}  // namespace anisomesh

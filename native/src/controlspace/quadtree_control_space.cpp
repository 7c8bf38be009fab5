#include "anisomesh/controlspace/quadtree_control_space.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "judge_in_slices.h"

namespace anisomesh {
namespace {
// Leaf sides as (corner a, corner b, mid-edge node) indices in a leaf's node list, and
// the corners' offsets in units of the leaf's span.
constexpr int kLeafSides[4][3] = {{0, 1, 4}, {1, 2, 5}, {3, 2, 6}, {0, 3, 7}};
constexpr int kCornerOffsets[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
// All 8 nodes of a leaf (corners, then mid-edge nodes) in units of half its span.
constexpr int kNodeHalfOffsets[8][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}, {1, 2}, {0, 1}};
}  // namespace
namespace {

constexpr std::uint64_t kEmptyKey = ~std::uint64_t{0};

std::uint64_t latticeKey(int x, int y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) | static_cast<std::uint32_t>(y);
}

size_t hashSlot(std::uint64_t key, size_t mask) {
  // splitmix64 finalizer: every key bit reaches the low bits used by the mask.
  key ^= key >> 30;
  key *= 0xBF58476D1CE4E5B9ull;
  key ^= key >> 27;
  key *= 0x94D049BB133111EBull;
  key ^= key >> 31;
  return static_cast<size_t>(key) & mask;
}

bool validBox(const Box2& b) {
  return b.lo.allFinite() && b.hi.allFinite() && b.hi.x() > b.lo.x() && b.hi.y() > b.lo.y();
}

// Table 1, quadratic column (eta along x, xi along y).
inline void serendipityWeights(double e, double x, double* n) {
  n[0] = (1 - e) * (1 - x) * (1 - 2 * e - 2 * x);
  n[1] = e * (1 - x) * (2 * e - 2 * x - 1);
  n[2] = e * x * (2 * e + 2 * x - 3);
  n[3] = (1 - e) * x * (2 * x - 2 * e - 1);
  n[4] = 4 * e * (1 - e) * (1 - x);
  n[5] = 4 * e * x * (1 - x);
  n[6] = 4 * e * (1 - e) * x;
  n[7] = 4 * (1 - e) * x * (1 - x);
}

}  // namespace

QuadtreeControlSpace::QuadtreeControlSpace(const Box2& box, const QuadtreeOptions& options)
    : options_(options), interp_(options.interpolation) {
  require(validBox(box), ErrorCode::InvalidDomain,
          "quadtree control space needs a finite box with lo < hi in both axes");
  require(options.maxLevel >= 0 && options.maxLevel <= 24, ErrorCode::InvalidArgument,
          "quadtree maxLevel must be in [0, 24], got " + std::to_string(options.maxLevel));
  require(options.initialLevel >= 0 && options.initialLevel <= std::min(options.maxLevel, 10),
          ErrorCode::InvalidArgument,
          "quadtree initialLevel must be in [0, min(maxLevel, 10)], got " + std::to_string(options.initialLevel));
  box_ = box;
  nodesPerLeaf_ = interp_ == QuadtreeInterpolation::Bilinear ? 4 : 8;
  bits_ = options.maxLevel + 1;
  rootLevel_ = options.initialLevel;
  rootSide_ = 1 << rootLevel_;
  const double r = static_cast<double>(latticeSize());
  scale_ = Vec2(r / (box.hi.x() - box.lo.x()), r / (box.hi.y() - box.lo.y()));
  cellScale_ = Vec2(1.0 / scale_.x(), 1.0 / scale_.y());
  latticeMax_ = r;

  mapKeys_.assign(1024, kEmptyKey);
  mapVals_.assign(1024, -1);

  const Metric placeholder = options.initialMetric ? *options.initialMetric : Metric::isotropic(box.size().norm());
  const SymMt pm = toSymMt(placeholder);
  const bool init = options.initialMetric.has_value();
  const int span = cellSpan(rootLevel_);
  rootGrid_.resize(static_cast<size_t>(rootSide_) * rootSide_);
  for (int j = 0; j < rootSide_; ++j) {
    for (int i = 0; i < rootSide_; ++i) {
      const int c = static_cast<int>(child_.size());
      child_.push_back(-1);
      level_.push_back(static_cast<std::uint8_t>(rootLevel_));
      ix_.push_back(i * span);
      iy_.push_back(j * span);
      cellNodes_.resize(cellNodes_.size() + nodesPerLeaf_, -1);
      rootGrid_[static_cast<size_t>(j) * rootSide_ + i] = c;
    }
  }
  leafCount_ = static_cast<int>(child_.size());
  for (int c = 0; c < leafCount_; ++c) {
    for (int k = 0; k < nodesPerLeaf_; ++k) {
      bool created = false;
      const int x = ix_[c] + kNodeHalfOffsets[k][0] * span / 2, y = iy_[c] + kNodeHalfOffsets[k][1] * span / 2;
      int n = findNode(x, y);
      if (n < 0) {
        n = findOrCreateNode(x, y, -1, created);
        mt_[n] = pm;
        if (init) flags_[n] |= kInitialized;
      }
      cellNodes_[static_cast<size_t>(c) * nodesPerLeaf_ + k] = n;
    }
  }
  constraintsDirty_ = true;
  rebuildConstraints();
}

Box2 QuadtreeControlSpace::cellBox(int cell) const {
  const int s = cellSpan(level_[cell]);
  const double r = latticeMax_;
  Box2 b;
  const Vec2 size = box_.size();
  b.lo = Vec2(box_.lo.x() + size.x() * (ix_[cell] / r), box_.lo.y() + size.y() * (iy_[cell] / r));
  b.hi = Vec2(box_.lo.x() + size.x() * ((ix_[cell] + s) / r), box_.lo.y() + size.y() * ((iy_[cell] + s) / r));
  return b;
}

int QuadtreeControlSpace::descend(int x, int y, int maxDepth) const {
  const int rs = bits_ - rootLevel_;
  int c = rootGrid_[static_cast<size_t>(y >> rs) * rootSide_ + (x >> rs)];
  int lvl = rootLevel_;
  while (lvl < maxDepth) {
    const int ch = child_[c];
    if (ch < 0) break;
    ++lvl;
    const int sh = bits_ - lvl;
    c = ch + ((x >> sh) & 1) + (((y >> sh) & 1) << 1);
  }
  return c;
}

int QuadtreeControlSpace::findNode(int x, int y) const {
  const std::uint64_t key = latticeKey(x, y);
  const size_t mask = mapKeys_.size() - 1;
  for (size_t s = hashSlot(key, mask);; s = (s + 1) & mask) {
    if (mapKeys_[s] == key) return mapVals_[s];
    if (mapKeys_[s] == kEmptyKey) return -1;
  }
}

void QuadtreeControlSpace::growMap() {
  std::vector<std::uint64_t> keys(mapKeys_.size() * 2, kEmptyKey);
  std::vector<std::int32_t> vals(mapKeys_.size() * 2, -1);
  const size_t mask = keys.size() - 1;
  for (size_t i = 0; i < mapKeys_.size(); ++i) {
    if (mapKeys_[i] == kEmptyKey) continue;
    size_t s = hashSlot(mapKeys_[i], mask);
    while (keys[s] != kEmptyKey) s = (s + 1) & mask;
    keys[s] = mapKeys_[i];
    vals[s] = mapVals_[i];
  }
  mapKeys_.swap(keys);
  mapVals_.swap(vals);
}

int QuadtreeControlSpace::findOrCreateNode(int x, int y, int parentCell, bool& created) {
  created = false;
  if ((mapUsed_ + 1) * 2 > mapKeys_.size()) growMap();
  const std::uint64_t key = latticeKey(x, y);
  const size_t mask = mapKeys_.size() - 1;
  size_t s = hashSlot(key, mask);
  for (;; s = (s + 1) & mask) {
    if (mapKeys_[s] == key) return mapVals_[s];
    if (mapKeys_[s] == kEmptyKey) break;
  }
  const double r = latticeMax_;
  const Vec2 size = box_.size();
  const Vec2 p(box_.lo.x() + size.x() * (x / r), box_.lo.y() + size.y() * (y / r));
  SymMt value;
  bool init = false;
  if (parentCell >= 0) {
    // The new node takes the parent's interpolation: refinement does not change the field.
    const int span = cellSpan(level_[parentCell]);
    value = interpolateInCell(parentCell, double(x - ix_[parentCell]) / span, double(y - iy_[parentCell]) / span);
    init = true;
    const int* nodes = leafNodes(parentCell);
    for (int k = 0; k < nodesPerLeaf_; ++k) init = init && nodeIsInitialized(nodes[k]);
  }
  const int n = addNode(p, value, init);
  mapKeys_[s] = key;
  mapVals_[s] = n;
  ++mapUsed_;
  created = true;
  return n;
}

SymMt QuadtreeControlSpace::interpolateInCell(int cell, double e, double x) const {
  const int* nd = leafNodes(cell);
  SymMt r{0.0, 0.0, 0.0};
  if (nodesPerLeaf_ == 4) {
    const double w[4] = {(1 - e) * (1 - x), e * (1 - x), e * x, (1 - e) * x};
    for (int k = 0; k < 4; ++k) {
      const SymMt& m = mt_[nd[k]];
      r.a += w[k] * m.a;
      r.b += w[k] * m.b;
      r.c += w[k] * m.c;
    }
  } else {
    double w[8];
    serendipityWeights(e, x, w);
    for (int k = 0; k < 8; ++k) {
      const SymMt& m = mt_[nd[k]];
      r.a += w[k] * m.a;
      r.b += w[k] * m.b;
      r.c += w[k] * m.c;
    }
  }
  return r;
}

// The leaf holding p (clamped onto the box; NaN goes to the lo corner) and p's local
// coordinates (eta, xi) in it: the descent every query shares.
inline int QuadtreeControlSpace::locateInLeaf(const Vec2& p, double& e, double& x) const {
  // Lattice coordinates, clamped (NaN goes to 0).
  double ux = (p.x() - box_.lo.x()) * scale_.x();
  double uy = (p.y() - box_.lo.y()) * scale_.y();
  ux = ux > 0.0 ? ux : 0.0;
  uy = uy > 0.0 ? uy : 0.0;
  ux = ux < latticeMax_ ? ux : latticeMax_;
  uy = uy < latticeMax_ ? uy : latticeMax_;
  const int last = latticeSize() - 1;
  const int qx = std::min(static_cast<int>(ux), last);
  const int qy = std::min(static_cast<int>(uy), last);
  const int rs = bits_ - rootLevel_;
  int c = rootGrid_[static_cast<size_t>(qy >> rs) * rootSide_ + (qx >> rs)];
  int lvl = rootLevel_;
  const std::int32_t* child = child_.data();
  for (int ch = child[c]; ch >= 0; ch = child[c]) {
    ++lvl;
    const int sh = bits_ - lvl;
    c = ch + ((qx >> sh) & 1) + (((qy >> sh) & 1) << 1);
  }
  const int sh = bits_ - lvl;
  const double inv = 1.0 / static_cast<double>(1 << sh);
  e = (ux - static_cast<double>((qx >> sh) << sh)) * inv;
  x = (uy - static_cast<double>((qy >> sh) << sh)) * inv;
  return c;
}

SymMt QuadtreeControlSpace::mtAt(const Vec2& p) const {
  double e, x;
  const int c = locateInLeaf(p, e, x);
  return interpolateInCell(c, e, x);
}

InterpolationStencil QuadtreeControlSpace::stencilAt(const Vec2& p) const {
  double e, x;
  const int c = locateInLeaf(p, e, x);
  const int* nd = leafNodes(c);
  InterpolationStencil s;
  s.count = nodesPerLeaf_;
  if (nodesPerLeaf_ == 4) {
    const double w[4] = {(1 - e) * (1 - x), e * (1 - x), e * x, (1 - e) * x};
    for (int k = 0; k < 4; ++k) s.weights[size_t(k)] = w[k];
  } else {
    serendipityWeights(e, x, s.weights.data());
  }
  for (int k = 0; k < s.count; ++k) s.nodes[size_t(k)] = nd[k];
  return s;
}

Metric QuadtreeControlSpace::metricAt(const Vec2& p) const { return toMetric(mtAt(p)); }

int QuadtreeControlSpace::locateLeaf(const Vec2& p) const {
  double ux = (p.x() - box_.lo.x()) * scale_.x();
  double uy = (p.y() - box_.lo.y()) * scale_.y();
  ux = ux > 0.0 ? ux : 0.0;
  uy = uy > 0.0 ? uy : 0.0;
  const int last = latticeSize() - 1;
  const int qx = ux < last ? static_cast<int>(ux) : last;
  const int qy = uy < last ? static_cast<int>(uy) : last;
  return descend(qx, qy, 1 << 30);
}

void QuadtreeControlSpace::splitLeafImpl(int c) {
  if (child_[c] >= 0 || level_[c] >= options_.maxLevel) return;
  const int lvl = level_[c];
  const int s = cellSpan(lvl);
  const int r = latticeSize();
  // Balance: every edge neighbour must be at least at this level before the split.
  for (int side = 0; side < 4; ++side) {
    int x = ix_[c], y = iy_[c];
    if (side == 0) x -= 1;
    if (side == 1) x += s;
    if (side == 2) y -= 1;
    if (side == 3) y += s;
    if (x < 0 || y < 0 || x >= r || y >= r) continue;
    for (;;) {
      const int n = descend(x, y, lvl);
      if (level_[n] >= lvl) break;
      splitLeafImpl(n);
    }
  }
  const int first = static_cast<int>(child_.size());
  const int h = s / 2;
  for (int k = 0; k < 4; ++k) {
    child_.push_back(-1);
    level_.push_back(static_cast<std::uint8_t>(lvl + 1));
    ix_.push_back(ix_[c] + (k & 1) * h);
    iy_.push_back(iy_[c] + (k >> 1) * h);
    cellNodes_.resize(cellNodes_.size() + nodesPerLeaf_, -1);
  }
  for (int k = 0; k < 4; ++k) {
    const int cc = first + k;
    for (int j = 0; j < nodesPerLeaf_; ++j) {
      bool created = false;
      const int n = findOrCreateNode(ix_[cc] + kNodeHalfOffsets[j][0] * h / 2, iy_[cc] + kNodeHalfOffsets[j][1] * h / 2,
                                     c, created);
      cellNodes_[static_cast<size_t>(cc) * nodesPerLeaf_ + j] = n;
    }
  }
  child_[c] = first;
  leafCount_ += 3;
  constraintsDirty_ = true;
}

void QuadtreeControlSpace::splitLeaf(int cell) {
  require(cell >= 0 && cell < cellCount(), ErrorCode::InvalidArgument, "splitLeaf: no such cell");
  splitLeafImpl(cell);
  rebuildConstraints();
}

void QuadtreeControlSpace::rebuildConstraints() const {
  if (!constraintsDirty_) return;
  constraints_.clear();
  readerStart_.clear();
  auto& flags = const_cast<std::vector<std::uint8_t>&>(flags_);
  for (auto& f : flags) f &= static_cast<std::uint8_t>(~kDependent);
  for (int c = 0; c < cellCount(); ++c) {
    if (child_[c] >= 0) continue;
    const int s = cellSpan(level_[c]);
    const int* nd = leafNodes(c);
    for (const auto& sd : kLeafSides) {
      const int ax = ix_[c] + kCornerOffsets[sd[0]][0] * s, ay = iy_[c] + kCornerOffsets[sd[0]][1] * s;
      const int bx = ix_[c] + kCornerOffsets[sd[1]][0] * s, by = iy_[c] + kCornerOffsets[sd[1]][1] * s;
      if (nodesPerLeaf_ == 4) {
        const int n = findNode((ax + bx) / 2, (ay + by) / 2);
        if (n >= 0) constraints_.push_back({n, level_[c], {nd[sd[0]], nd[sd[1]], nd[sd[1]]}, {0.5, 0.5, 0.0}});
      } else if (s >= 4) {
        const int n1 = findNode(ax + (bx - ax) / 4, ay + (by - ay) / 4);
        const int n3 = findNode(ax + 3 * (bx - ax) / 4, ay + 3 * (by - ay) / 4);
        // Quadratic along the coarse side through a, mid, b at 1/4 and 3/4.
        if (n1 >= 0) constraints_.push_back({n1, level_[c], {nd[sd[0]], nd[sd[2]], nd[sd[1]]}, {0.375, 0.75, -0.125}});
        if (n3 >= 0) constraints_.push_back({n3, level_[c], {nd[sd[0]], nd[sd[2]], nd[sd[1]]}, {-0.125, 0.75, 0.375}});
      }
    }
  }
  // Coarser sides first: a master may itself hang on an even coarser side (bilinear).
  std::stable_sort(constraints_.begin(), constraints_.end(), [](const Constraint& a, const Constraint& b) {
    return a.level != b.level ? a.level < b.level : a.node < b.node;
  });
  for (const auto& k : constraints_) flags[k.node] |= kDependent;
  // A master hanging on a coarser side comes earlier (sorted by level); checked, since
  // applyConstraintsTouched() relies on it.
  std::vector<int> rank(flags.size(), -1);
  constraintsOrdered_ = true;
  for (size_t r = 0; r < constraints_.size(); ++r) {
    for (int j = 0; j < 3; ++j) {
      const int m = constraints_[r].master[j];
      if ((flags[m] & kDependent) && (rank[m] < 0)) constraintsOrdered_ = false;
    }
    rank[constraints_[r].node] = static_cast<int>(r);
  }
  constraintsDirty_ = false;
}

void QuadtreeControlSpace::applyConstraint(const Constraint& k) {
  SymMt r{0.0, 0.0, 0.0};
  bool init = true;
  for (int j = 0; j < 3; ++j) {
    const SymMt& m = mt_[k.master[j]];
    r.a += k.weight[j] * m.a;
    r.b += k.weight[j] * m.b;
    r.c += k.weight[j] * m.c;
    init = init && (k.weight[j] == 0.0 || nodeIsInitialized(k.master[j]));
  }
  mt_[k.node] = r;
  if (init) flags_[k.node] |= kInitialized;
}

void QuadtreeControlSpace::applyConstraints() {
  rebuildConstraints();
  for (const auto& k : constraints_) applyConstraint(k);
}

void QuadtreeControlSpace::applyConstraintsTouched(std::vector<char>& touched, const std::vector<int>& touchedList,
                                                   std::vector<RewrittenNode>& rewritten) {
  rebuildConstraints();
  if (!constraintsOrdered_) {
    // Out of order, a constraint may read a master rewritten after it: evaluate them all.
    for (const auto& k : constraints_) {
      rewritten.push_back({k.node, mt_[k.node]});
      applyConstraint(k);
      touched[k.node] = 1;
    }
    return;
  }
  // The pass over constraints_ in order that rewrites those whose node or a master is
  // flagged (a rewritten node is flagged at once), visiting only those: the constraints
  // that read a flagged node, smallest index first, each one's node's readers joining
  // when it is rewritten (only those after it: the pass has gone by the others).
  const int nc = static_cast<int>(constraints_.size());
  if (readerStart_.size() != static_cast<size_t>(nodeCount()) + 1) {
    readerStart_.assign(nodeCount() + 1, 0);
    for (const auto& k : constraints_) {
      ++readerStart_[k.node + 1];
      for (int j = 0; j < 3; ++j) ++readerStart_[k.master[j] + 1];
    }
    for (int i = 0; i < nodeCount(); ++i) readerStart_[i + 1] += readerStart_[i];
    readers_.assign(readerStart_.back(), 0);
    std::vector<std::int32_t> at(readerStart_.begin(), readerStart_.end() - 1);
    for (int r = 0; r < nc; ++r) {
      const auto& k = constraints_[r];
      readers_[at[k.node]++] = r;
      for (int j = 0; j < 3; ++j) readers_[at[k.master[j]]++] = r;
    }
  }
  constraintQueued_.resize(nc, 0);
  std::vector<int> queue;  // min-heap of constraint indices
  auto enqueueReaders = [&](int node, int after) {
    for (int e = readerStart_[node]; e < readerStart_[node + 1]; ++e) {
      const int r = readers_[e];
      if (r <= after || constraintQueued_[r]) continue;
      constraintQueued_[r] = 1;
      queue.push_back(r);
      std::push_heap(queue.begin(), queue.end(), std::greater<int>());
    }
  };
  for (int i : touchedList) enqueueReaders(i, -1);
  while (!queue.empty()) {
    std::pop_heap(queue.begin(), queue.end(), std::greater<int>());
    const int r = queue.back();
    queue.pop_back();
    constraintQueued_[r] = 0;
    const auto& k = constraints_[r];
    rewritten.push_back({k.node, mt_[k.node]});
    applyConstraint(k);
    if (!touched[k.node]) {
      touched[k.node] = 1;
      enqueueReaders(k.node, r);
    }
  }
}

std::vector<AdaptiveControlSpace::HangingNode> QuadtreeControlSpace::hangingNodes() const {
  rebuildConstraints();
  std::vector<HangingNode> out;
  out.reserve(constraints_.size());
  for (const auto& k : constraints_)
    out.push_back({k.node, {k.master[0], k.master[1], k.master[2]}, {k.weight[0], k.weight[1], k.weight[2]}});
  return out;
}

std::vector<std::array<int, 2>> QuadtreeControlSpace::rawEdges(bool structure) const {
  rebuildConstraints();
  const bool freeOnly = !structure;
  std::vector<std::array<int, 2>> edges;
  edges.reserve(static_cast<size_t>(leafCount_) * (nodesPerLeaf_ == 4 ? 5 : 9));
  for (int c = 0; c < cellCount(); ++c) {
    if (child_[c] >= 0) continue;
    const int s = cellSpan(level_[c]);
    const int* nd = leafNodes(c);
    for (const auto& sd : kLeafSides) {
      const int ax = ix_[c] + kCornerOffsets[sd[0]][0] * s, ay = iy_[c] + kCornerOffsets[sd[0]][1] * s;
      const int bx = ix_[c] + kCornerOffsets[sd[1]][0] * s, by = iy_[c] + kCornerOffsets[sd[1]][1] * s;
      int chain[5];
      int n = 0;
      chain[n++] = nd[sd[0]];
      if (nodesPerLeaf_ == 4) {
        chain[n++] = findNode((ax + bx) / 2, (ay + by) / 2);
      } else {
        chain[n++] = s >= 4 ? findNode(ax + (bx - ax) / 4, ay + (by - ay) / 4) : -1;
        chain[n++] = nd[sd[2]];
        chain[n++] = s >= 4 ? findNode(ax + 3 * (bx - ax) / 4, ay + 3 * (by - ay) / 4) : -1;
      }
      chain[n++] = nd[sd[1]];
      int prev = -1;
      for (int i = 0; i < n; ++i) {
        const int v = chain[i];
        if (v < 0 || (freeOnly && !nodeIsFree(v))) continue;
        if (prev >= 0) edges.push_back({std::min(prev, v), std::max(prev, v)});
        prev = v;
      }
    }
  }
  return edges;
}

std::vector<std::vector<int>> QuadtreeControlSpace::elementNodes() const {
  std::vector<std::vector<int>> out;
  out.reserve(leafCount_);
  for (int c = 0; c < cellCount(); ++c) {
    if (child_[c] >= 0) continue;
    const int* nd = leafNodes(c);
    out.push_back({nd[0], nd[1], nd[2], nd[3]});
  }
  return out;
}

std::vector<int> QuadtreeControlSpace::leaves() const {
  std::vector<int> out;
  out.reserve(leafCount_);
  for (int c = 0; c < cellCount(); ++c)
    if (child_[c] < 0) out.push_back(c);
  return out;
}

std::vector<int> QuadtreeControlSpace::leavesNear(const std::vector<Box2>& near) const {
  // A cell's box holds its children's (cellBox rounds monotonically in the lattice
  // coordinates), so a cell that meets no box is skipped with its subtree.
  auto meets = [&](int c) {
    const Box2 b = cellBox(c);
    for (const Box2& r : near)
      if (!(r.hi.x() < b.lo.x() || r.lo.x() > b.hi.x() || r.hi.y() < b.lo.y() || r.lo.y() > b.hi.y())) return true;
    return false;
  };
  std::vector<int> out, stack(rootGrid_.begin(), rootGrid_.end());
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    if (!meets(c)) continue;
    if (child_[c] < 0)
      out.push_back(c);
    else
      for (int k = 0; k < 4; ++k) stack.push_back(child_[c] + k);
  }
  std::sort(out.begin(), out.end());
  return out;
}

ControlElement QuadtreeControlSpace::elementOf(int cell) const {
  ControlElement e;
  e.id = cell;
  e.box = cellBox(cell);
  const Vec2 sz = e.box.size();
  e.size = std::max(sz.x(), sz.y());
  e.nodeCount = nodesPerLeaf_;
  const int* nd = leafNodes(cell);
  for (int k = 0; k < nodesPerLeaf_; ++k) e.nodes[k] = nd[k];
  const double f[5][2] = {{0.5, 0.5}, {0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
  e.sampleCount = 5;
  for (int k = 0; k < 5; ++k) e.samples[k] = e.box.lo + Vec2(f[k][0] * sz.x(), f[k][1] * sz.y());
  return e;
}

void QuadtreeControlSpace::refine(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) {
  refineFrom(leaves(), pred, onNewNodes);
}

void QuadtreeControlSpace::refineNear(const std::vector<Box2>& near, const ElementPredicate& pred,
                                      const NewNodesCallback& onNewNodes) {
  refineFrom(leavesNear(near), pred, onNewNodes);
}

void QuadtreeControlSpace::refineConcurrently(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) {
  refineFrom(leaves(), pred, onNewNodes, true);
}

void QuadtreeControlSpace::refineFrom(std::vector<int> work, const ElementPredicate& pred,
                                      const NewNodesCallback& onNewNodes, bool readOnly) {
  rebuildConstraints();
  std::vector<int> split;
  std::vector<char> verdict;
  auto wanted = [&](int c) { return child_[c] < 0 && level_[c] < options_.maxLevel && pred(elementOf(c)); };
  while (!work.empty()) {
    split.clear();
    // Decide the whole batch on the current field, then split.
    if (readOnly && threadCount() > 1) {
      // Slices of the batch in parallel chunks, the progress ticks on this thread between
      // them; the split list in batch order, as one thread makes it.
      verdict.assign(work.size(), 0);
      controlspace_internal::judgeInSlices(
          work.size(), 8192, 256, [&](size_t k) { verdict[k] = wanted(work[k]) ? 1 : 0; }, [&] { refinementTick(); });
      for (size_t k = 0; k < work.size(); ++k)
        if (verdict[k]) split.push_back(work[k]);
    } else {
      for (int c : work) {
        refinementTick();
        if (wanted(c)) split.push_back(c);
      }
    }
    if (split.empty()) break;
    // A split adds a centre and up to 4 mid-edge lattice nodes, about 3 new ones on
    // average (shared with neighbours); serendipity leaves about 8.
    checkRefinementEstimate(std::int64_t(split.size()), nodesPerLeaf_ == 4 ? 3.0 : 8.0);
    const int nodesBefore = nodeCount();
    const int cellsBefore = cellCount();
    for (int c : split) {
      refinementTick();
      splitLeafImpl(c);
    }
    checkRefinementEstimate(0, 0.0);  // balancing may have split more than the batch
    rebuildConstraints();
    if (onNewNodes) onNewNodes(nodesBefore, nodeCount());
    applyConstraints();
    work.clear();
    for (int c = cellsBefore; c < cellCount(); ++c)
      if (child_[c] < 0) work.push_back(c);
  }
}

void QuadtreeControlSpace::refineByDifference(double threshold) {
  require(threshold >= 0.0, ErrorCode::InvalidArgument, "refinement threshold must be >= 0");
  refine(
      [&](const ControlElement& e) {
        for (int i = 0; i < e.nodeCount; ++i)
          for (int j = i + 1; j < e.nodeCount; ++j)
            if (difference(nodeMetric(e.nodes[i]), nodeMetric(e.nodes[j])) > threshold) return true;
        return false;
      },
      nullptr);
}

std::vector<double> QuadtreeControlSpace::nodeElementSizes() const {
  std::vector<double> out(nodeCount(), std::numeric_limits<double>::infinity());
  const Vec2 sz = box_.size();
  for (int c = 0; c < cellCount(); ++c) {
    if (child_[c] >= 0) continue;
    const double f = static_cast<double>(cellSpan(level_[c])) / latticeMax_;
    const double s = std::max(sz.x(), sz.y()) * f;
    const int* nd = leafNodes(c);
    for (int k = 0; k < nodesPerLeaf_; ++k) out[nd[k]] = std::min(out[nd[k]], s);
  }
  return out;
}

double QuadtreeControlSpace::minElementSize() const {
  const Vec2 sz = box_.size();
  return std::max(sz.x(), sz.y()) / static_cast<double>(1 << options_.maxLevel);
}

bool QuadtreeControlSpace::isBalanced() const {
  const int r = latticeSize();
  for (int c = 0; c < cellCount(); ++c) {
    if (child_[c] >= 0) continue;
    const int lvl = level_[c];
    const int s = cellSpan(lvl);
    if (s < 4) continue;  // no leaf can be two levels deeper
    for (int side = 0; side < 4; ++side) {
      for (int k = 0; k < 4; ++k) {
        int x = ix_[c], y = iy_[c];
        const int along = k * (s / 4);
        if (side == 0) {
          x -= 1;
          y += along;
        }
        if (side == 1) {
          x += s;
          y += along;
        }
        if (side == 2) {
          y -= 1;
          x += along;
        }
        if (side == 3) {
          y += s;
          x += along;
        }
        if (x < 0 || y < 0 || x >= r || y >= r) continue;
        if (level_[descend(x, y, 1 << 30)] >= lvl + 2) return false;
      }
    }
  }
  return true;
}

size_t QuadtreeControlSpace::memoryBytes() const {
  return child_.capacity() * 4 + level_.capacity() + ix_.capacity() * 4 + iy_.capacity() * 4 +
         cellNodes_.capacity() * 4 + rootGrid_.capacity() * 4 + mapKeys_.capacity() * 8 + mapVals_.capacity() * 4 +
         pos_.capacity() * sizeof(Vec2) + mt_.capacity() * sizeof(SymMt) + flags_.capacity() +
         constraints_.capacity() * sizeof(Constraint) + edgeGraphBytes();
}

}  // namespace anisomesh

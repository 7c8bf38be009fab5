#pragma once
// A uniform bucket grid over boxes: the spatial index with which the discrete sources and
// the minimum of two control spaces find what lies near a control node, and domain
// decomposition finds the boundary edges near a cut.
#include <algorithm>
#include <cmath>
#include <vector>

#include "anisomesh/core/int_conversion.h"
#include "anisomesh/core/types.h"

namespace anisomesh {

// Uniform bucket grid over a box holding item indices by bounding box (an item lands in
// every bucket its box overlaps): items are found by box.
class BucketGrid {
 public:
  BucketGrid(const Box2& domain, const std::vector<Box2>& boxes) : domain_(domain) {
    const double n = static_cast<double>(boxes.size());
    side_ = std::clamp(static_cast<int>(std::sqrt(n / 2.0)) + 1, 1, 1024);
    const Vec2 sz = domain.size();
    inv_ = Vec2(side_ / std::max(sz.x(), 1e-300), side_ / std::max(sz.y(), 1e-300));
    std::vector<int> count(static_cast<size_t>(side_) * side_ + 1, 0);
    auto forCells = [&](const Box2& b, auto&& fn) {
      int i0, i1, j0, j1;
      if (!range(b, i0, i1, j0, j1)) return;
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) fn(j * side_ + i);
    };
    for (const Box2& b : boxes) forCells(b, [&](int c) { ++count[c + 1]; });
    for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    start_ = count;
    items_.resize(count.back());
    for (size_t k = 0; k < boxes.size(); ++k)
      forCells(boxes[k], [&](int c) { items_[count[c]++] = static_cast<int>(k); });
  }

  // Calls fn(item) for items in buckets overlapping b (an item may come more than once
  // when its box spans several buckets); stops early when fn returns true.
  template <class F>
  bool any(const Box2& b, F&& fn) const {
    int i0, i1, j0, j1;
    if (!range(b, i0, i1, j0, j1)) return false;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const int c = j * side_ + i;
        for (int k = start_[c]; k < start_[c + 1]; ++k)
          if (fn(items_[k])) return true;
      }
    return false;
  }

  // Calls fn(slot) for the slots (indices into items()) of the buckets overlapping b; the
  // slots of one row of buckets are consecutive, so data stored in slot order is scanned
  // contiguously.
  template <class F>
  void forSlots(const Box2& b, F&& fn) const {
    int i0, i1, j0, j1;
    if (!range(b, i0, i1, j0, j1)) return;
    for (int j = j0; j <= j1; ++j)
      for (int k = start_[j * side_ + i0], end = start_[j * side_ + i1 + 1]; k < end; ++k) fn(k);
  }
  // Same, stopping early when fn returns true; returns whether it did.
  template <class F>
  bool anySlot(const Box2& b, F&& fn) const {
    int i0, i1, j0, j1;
    if (!range(b, i0, i1, j0, j1)) return false;
    for (int j = j0; j <= j1; ++j)
      for (int k = start_[j * side_ + i0], end = start_[j * side_ + i1 + 1]; k < end; ++k)
        if (fn(k)) return true;
    return false;
  }
  // Item of each slot (bucket by bucket).
  const std::vector<int>& items() const { return items_; }

 private:
  bool range(const Box2& b, int& i0, int& i1, int& j0, int& j1) const {
    if (b.hi.x() < domain_.lo.x() || b.hi.y() < domain_.lo.y() || b.lo.x() > domain_.hi.x() ||
        b.lo.y() > domain_.hi.y())
      return false;
    auto cell = [&](double v, double lo, double inv) { return clampedCell((v - lo) * inv, side_); };
    i0 = cell(b.lo.x(), domain_.lo.x(), inv_.x());
    i1 = cell(b.hi.x(), domain_.lo.x(), inv_.x());
    j0 = cell(b.lo.y(), domain_.lo.y(), inv_.y());
    j1 = cell(b.hi.y(), domain_.lo.y(), inv_.y());
    return true;
  }

  Box2 domain_;
  int side_ = 1;
  Vec2 inv_;
  std::vector<int> start_, items_;
};

}  // namespace anisomesh

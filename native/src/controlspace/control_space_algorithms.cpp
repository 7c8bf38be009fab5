#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"

namespace anisomesh {
namespace {

// Uniform bucket grid over a box holding item indices by bounding box (an item lands in
// every bucket its box overlaps): the spatial index of sources and nodes here.
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
    auto cell = [&](double v, double lo, double inv) {
      return std::clamp(static_cast<int>(std::floor((v - lo) * inv)), 0, side_ - 1);
    };
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

Box2 pointBox(const Vec2& p, double r) {
  Box2 b;
  b.lo = p - Vec2(r, r);
  b.hi = p + Vec2(r, r);
  return b;
}

Box2 pieceBox(const SourcePiece& s, double r) {
  Box2 b;
  b.lo = s.a.cwiseMin(s.b) - Vec2(r, r);
  b.hi = s.a.cwiseMax(s.b) + Vec2(r, r);
  return b;
}

bool elementNodesDiffer(const AdaptiveControlSpace& cs, const ControlElement& e, double threshold) {
  for (int i = 0; i < e.nodeCount; ++i)
    for (int j = i + 1; j < e.nodeCount; ++j)
      if (difference(cs.nodeMetric(e.nodes[i]), cs.nodeMetric(e.nodes[j])) > threshold) return true;
  return false;
}

}  // namespace

std::vector<std::array<int, 2>> AdaptiveControlSpace::sortedEdges(bool structure) const {
  std::vector<std::array<int, 2>> edges = rawEdges(structure);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

void AdaptiveControlSpace::edgeGraph(bool structure, std::vector<int>& start, std::vector<int>& nbr) const {
  const std::vector<std::array<int, 2>> edges = rawEdges(structure);
  const int n = nodeCount();
  start.assign(n + 1, 0);
  for (const auto& e : edges) {
    ++start[e[0] + 1];
    ++start[e[1] + 1];
  }
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<int> all(start.back());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& e : edges) {
    all[fill[e[0]]++] = e[1];
    all[fill[e[1]]++] = e[0];
  }
  // Per node: sort the few neighbours (insertion sort) and drop repeats, compacting.
  nbr.resize(all.size());
  int out = 0;
  for (int i = 0; i < n; ++i) {
    const int b = start[i], e = start[i + 1];
    for (int k = b + 1; k < e; ++k) {
      const int v = all[k];
      int m = k;
      for (; m > b && all[m - 1] > v; --m) all[m] = all[m - 1];
      all[m] = v;
    }
    start[i] = out;
    for (int k = b; k < e; ++k)
      if (k == b || all[k] != all[k - 1]) nbr[out++] = all[k];
  }
  start[n] = out;
  nbr.resize(out);
}

std::vector<ControlNode> AdaptiveControlSpace::controlNodes() const {
  const std::vector<double> sizes = nodeElementSizes();
  std::vector<ControlNode> out;
  out.reserve(nodeCount());
  for (int i = 0; i < nodeCount(); ++i)
    if (nodeIsFree(i)) out.push_back({pos_[i], nodeMetric(i), sizes[i]});
  return out;
}

void insertSources(AdaptiveControlSpace& cs, const std::vector<MetricSource>& sources,
                   const DiscreteInsertionOptions& options) {
  const Box2 box = cs.bounds();
  const std::vector<SourcePiece> pieces = sourcePieces(sources, box, options.source);
  if (pieces.empty()) return;  // nothing inside the domain: no-op

  // (a) Structure adaptation near the sources.
  {
    std::vector<Box2> boxes;
    boxes.reserve(pieces.size());
    for (const auto& p : pieces) boxes.push_back(pieceBox(p, p.radius));
    const BucketGrid grid(box, boxes);
    // The pieces' boxes and target sizes in slot order: the scans read contiguous memory.
    struct Slot {
      Box2 box;
      double targetSize;
      int piece;
    };
    std::vector<Slot> slots;
    slots.reserve(grid.items().size());
    for (int k : grid.items()) slots.push_back({boxes[k], pieces[k].targetSize, k});
    cs.refine(
        [&](const ControlElement& e) {
          return grid.anySlot(e.box, [&](int k) {
            const Slot& sl = slots[k];
            if (!(e.size > sl.targetSize)) return false;
            // Boxes apart: the piece is farther than its radius (cheap exact rejection).
            if (sl.box.hi.x() < e.box.lo.x() || sl.box.lo.x() > e.box.hi.x() || sl.box.hi.y() < e.box.lo.y() ||
                sl.box.lo.y() > e.box.hi.y())
              return false;
            const SourcePiece& p = pieces[sl.piece];
            return segmentBoxDistance(p.a, p.b, e.box) <= p.radius;
          });
        },
        nullptr);
  }

  // (b) Weighted average of the sources reaching each free node. Free nodes are binned,
  // and their positions and sums kept in bin order (contiguous scans); every node still
  // accumulates its sources in their order.
  const int n = cs.nodeCount();
  const double minSize = cs.minElementSize();
  std::vector<Box2> nodeBoxes;
  std::vector<int> freeNodes;
  nodeBoxes.reserve(n);
  freeNodes.reserve(n);
  for (int i = 0; i < n; ++i)
    if (cs.nodeIsFree(i)) {
      freeNodes.push_back(i);
      nodeBoxes.push_back(pointBox(cs.nodePosition(i), 0.0));
    }
  const BucketGrid nodeGrid(box, nodeBoxes);
  const std::vector<int>& slotItem = nodeGrid.items();
  const size_t slots = slotItem.size();
  std::vector<Vec2> slotPos(slots);
  for (size_t k = 0; k < slots; ++k) slotPos[k] = cs.nodePosition(freeNodes[slotItem[k]]);
  std::vector<SymMt> sum(slots, SymMt{0.0, 0.0, 0.0});
  std::vector<double> wsum(slots, 0.0);
  for (const SourcePiece& p : pieces) {
    const double reach = std::max(p.targetSize, minSize);
    const double soft = 0.25 * reach;
    const double limit = p.radius + reach;
    const SymMt m = toSymMt(p.metric);
    auto add = [&](size_t k, double d) {
      const double t = std::max(d - p.radius, 0.0) + soft;
      const double w = 1.0 / (t * t);
      sum[k].a += w * m.a;
      sum[k].b += w * m.b;
      sum[k].c += w * m.c;
      wsum[k] += w;
    };
    if (p.a == p.b) {  // a point: the distance as distanceToPiece() computes it
      nodeGrid.forSlots(pieceBox(p, limit), [&](int k) {
        const double dx = p.a.x() - slotPos[k].x(), dy = p.a.y() - slotPos[k].y();
        const double d = std::sqrt(dx * dx + dy * dy);
        if (!(d > limit)) add(k, d);
      });
    } else {
      nodeGrid.forSlots(pieceBox(p, limit), [&](int k) {
        const double d = distanceToPiece(p, slotPos[k]);
        if (!(d > limit)) add(k, d);
      });
    }
  }
  for (size_t k = 0; k < slots; ++k) {
    if (wsum[k] <= 0.0) continue;
    const int i = freeNodes[slotItem[k]];
    const SymMt avg{sum[k].a / wsum[k], sum[k].b / wsum[k], sum[k].c / wsum[k]};
    const Metric m = toMetric(avg);
    cs.setNodeMetric(i, cs.nodeIsInitialized(i) ? intersect(cs.nodeMetric(i), m) : m);
  }

  // (c) Extrapolation into the nodes no source reached.
  const Metric fallback =
      options.fallbackMetric ? *options.fallbackMetric : Metric::isotropic(0.25 * box.size().norm());
  extrapolateMetric(cs, fallback);
}

int refineWhereMetricsDiffer(AdaptiveControlSpace& cs, double threshold) {
  require(threshold >= 0.0, ErrorCode::InvalidArgument, "refinement threshold must be >= 0");
  const int before = cs.elementCount();
  cs.refine([&](const ControlElement& e) { return elementNodesDiffer(cs, e, threshold); }, nullptr);
  return cs.elementCount() - before;
}

int extrapolateMetric(AdaptiveControlSpace& cs, const Metric& fallback) {
  const int n = cs.nodeCount();
  std::vector<char> known(n, 0);
  bool any = false;
  for (int i = 0; i < n; ++i) {
    known[i] = cs.nodeIsFree(i) && cs.nodeIsInitialized(i);
    any = any || known[i];
  }
  int filled = 0;
  if (any) {
    std::vector<int> start, nbr;
    cs.edgeGraph(false, start, nbr);
    // Breadth-first fronts: the unknown free neighbours of the nodes known so far.
    std::vector<int> front, next;
    std::vector<char> inFront(n, 0);
    for (int i = 0; i < n; ++i)
      if (known[i])
        for (int k = start[i]; k < start[i + 1]; ++k) {
          const int j = nbr[k];
          if (!known[j] && !inFront[j] && cs.nodeIsFree(j)) {
            inFront[j] = 1;
            front.push_back(j);
          }
        }
    std::vector<std::pair<int, SymMt>> values;
    while (!front.empty()) {
      std::sort(front.begin(), front.end());
      // Values of a whole front come from the previous fronts only (order independent).
      values.clear();
      for (int i : front) {
        SymMt s{0.0, 0.0, 0.0};
        double ws = 0.0;
        for (int k = start[i]; k < start[i + 1]; ++k) {
          const int j = nbr[k];
          if (!known[j]) continue;
          const double w = 1.0 / (cs.nodePosition(j) - cs.nodePosition(i)).squaredNorm();
          const SymMt& m = cs.nodeMt(j);
          s.a += w * m.a;
          s.b += w * m.b;
          s.c += w * m.c;
          ws += w;
        }
        values.push_back({i, SymMt{s.a / ws, s.b / ws, s.c / ws}});
      }
      for (const auto& [i, v] : values) {
        cs.setNodeMetric(i, toMetric(v));
        known[i] = 1;
        ++filled;
      }
      next.clear();
      for (int i : front)
        for (int k = start[i]; k < start[i + 1]; ++k) {
          const int j = nbr[k];
          if (!known[j] && !inFront[j] && cs.nodeIsFree(j)) {
            inFront[j] = 1;
            next.push_back(j);
          }
        }
      front.swap(next);
    }
  }
  for (int i = 0; i < n; ++i)
    if (!known[i] && cs.nodeIsFree(i)) {
      cs.setNodeMetric(i, fallback);
      ++filled;
    }
  cs.applyConstraints();
  return filled;
}

void insertMetricFunction(AdaptiveControlSpace& cs, const MetricFunction& f,
                          const ContinuousInsertionOptions& options) {
  require(static_cast<bool>(f), ErrorCode::InvalidArgument, "metric function is empty");
  require(options.threshold > 0.0, ErrorCode::InvalidArgument, "continuous insertion threshold must be > 0");
  const double sampleThreshold = options.sampleThreshold < 0.0 ? options.threshold : options.sampleThreshold;
  bool fresh = true;
  for (int i = 0; i < cs.nodeCount(); ++i)
    if (cs.nodeIsFree(i) && cs.nodeIsInitialized(i)) fresh = false;
  // The field before insertion: new nodes and samples compare against min(original, f),
  // not against an interpolation of already intersected values (which would compound).
  std::unique_ptr<AdaptiveControlSpace> original;
  if (!fresh) original = cs.clone();
  auto target = [&](const Vec2& p) {
    const Metric v = f(p);
    return fresh ? v : intersect(original->metricAt(p), v);
  };
  std::vector<Metric> values;
  auto setFromFunction = [&](int first, int last) {
    if (options.concurrent && fresh) {
      // f's values computed in parallel chunks, stored in node order (same result).
      values.resize(size_t(last - first));
      parallelChunks(values.size(), 1024, [&](size_t, size_t b, size_t e) {
        for (size_t k = b; k < e; ++k) {
          const int i = first + int(k);
          if (cs.nodeIsFree(i)) values[k] = f(cs.nodePosition(i));
        }
      });
      for (int i = first; i < last; ++i)
        if (cs.nodeIsFree(i)) cs.setNodeMetric(i, values[size_t(i - first)]);
      return;
    }
    for (int i = first; i < last; ++i) {
      if (!cs.nodeIsFree(i)) continue;
      const Vec2& p = cs.nodePosition(i);
      cs.setNodeMetric(i, fresh || !cs.nodeIsInitialized(i) ? f(p) : target(p));
    }
  };
  // The smallest size requested at the element's nodes (1 / sqrt of the largest eigenvalue of M).
  auto smallestNodeSize = [&](const ControlElement& e) {
    double h = std::numeric_limits<double>::infinity();
    for (int k = 0; k < e.nodeCount; ++k) {
      const SymMt& m = cs.nodeMt(e.nodes[k]);
      h = std::min(h, 1.0 / (0.5 * (m.a + m.c) + std::hypot(0.5 * (m.a - m.c), m.b)));
    }
    return h;
  };
  setFromFunction(0, cs.nodeCount());
  cs.applyConstraints();
  cs.refine(
      [&](const ControlElement& e) {
        if (options.domain && !options.domain(e.box)) return false;
        if (options.minMetricSize > 0.0 && e.size < options.minMetricSize * smallestNodeSize(e)) return false;
        if (elementNodesDiffer(cs, e, options.threshold)) return true;
        if (!options.checkSamples) return false;
        for (int k = 0; k < e.sampleCount; ++k)
          if (difference(cs.metricAt(e.samples[k]), target(e.samples[k])) > sampleThreshold) return true;
        return false;
      },
      setFromFunction);
}

void intersectControlSpace(AdaptiveControlSpace& cs1, const ControlSpace& cs2, const std::vector<ControlNode>& cs2Nodes,
                           const MinimumOptions& options) {
  require(options.threshold >= 0.0, ErrorCode::InvalidArgument, "minimum threshold must be >= 0");
  const std::unique_ptr<AdaptiveControlSpace> original = cs1.clone();
  auto phase1 = [&](int first, int last) {
    for (int i = first; i < last; ++i)
      if (cs1.nodeIsFree(i)) {
        const Vec2& p = cs1.nodePosition(i);
        cs1.setNodeMetric(i, intersect(original->metricAt(p), cs2.metricAt(p)));
      }
  };
  // Phase 1.
  phase1(0, cs1.nodeCount());
  cs1.applyConstraints();
  // Phase 2: the nodes of cs2 as discrete sources.
  std::vector<Box2> boxes;
  boxes.reserve(cs2Nodes.size());
  for (const auto& nd : cs2Nodes) boxes.push_back(pointBox(nd.position, 0.0));
  const BucketGrid grid(cs1.bounds(), boxes);
  cs1.refine(
      [&](const ControlElement& e) {
        return grid.any(e.box, [&](int k) {
          const ControlNode& nd = cs2Nodes[k];
          if (e.size <= nd.elementSize || !e.box.contains(nd.position)) return false;
          const Metric m = cs1.metricAt(nd.position);
          const Metric target = intersect(original->metricAt(nd.position), nd.metric);
          return difference(m, target) > options.threshold;
        });
      },
      phase1);
  // Phase 3: phase 1 again.
  phase1(0, cs1.nodeCount());
  cs1.applyConstraints();
  if (!options.conservative) return;
  // Phase 3, conservative: where the interpolation exceeds the exact minimum at sample
  // points of an element (sizes larger by e), the element's free nodes shrink by 1 + e
  // (the largest over their elements), so the result errs on the fine side; a few passes
  // because Mt interpolation is not exactly monotone.
  const std::vector<std::vector<int>> elements = cs1.elementNodes();
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<double> grow(cs1.nodeCount(), 1.0);
    bool any = false;
    for (const std::vector<int>& el : elements) {
      double worst = 1.0;
      auto check = [&](const Vec2& p) {
        const Metric r = cs1.metricAt(p);
        const Metric t = intersect(original->metricAt(p), cs2.metricAt(p));
        // Largest ratio of r's size to t's over all directions: sqrt(lmax(Mt_r^-1 M_t Mt_r^-1)).
        const Mat2 ir = r.transform().inverse();
        const Mat2 q = ir * t.tensor() * ir;
        const double half = 0.5 * (q(0, 0) - q(1, 1)), off = 0.5 * (q(0, 1) + q(1, 0));
        worst =
            std::max(worst, std::sqrt(std::max(0.5 * (q(0, 0) + q(1, 1)) + std::sqrt(half * half + off * off), 0.0)));
      };
      if (el.size() == 4) {  // leaf: a 4 x 4 grid of interior points
        const Vec2 lo = cs1.nodePosition(el[0]), hi = cs1.nodePosition(el[2]);
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            check(Vec2(lo.x() + (a + 0.5) / 4 * (hi.x() - lo.x()), lo.y() + (b + 0.5) / 4 * (hi.y() - lo.y())));
      } else {  // triangle: the points of barycentric coordinates in quarters, but vertices
        const Vec2 A = cs1.nodePosition(el[0]), B = cs1.nodePosition(el[1]), C = cs1.nodePosition(el[2]);
        for (int a = 0; a <= 4; ++a)
          for (int b = 0; a + b <= 4; ++b)
            if (a < 4 && b < 4 && a + b > 0) check((a * A + b * B + (4 - a - b) * C) / 4.0);
        check((A + B + C) / 3.0);
      }
      if (worst <= 1.0 + 1e-12) continue;
      any = true;
      for (int v : el) grow[v] = std::max(grow[v], worst);
    }
    if (!any) break;
    for (int i = 0; i < cs1.nodeCount(); ++i)
      if (grow[i] > 1.0 && cs1.nodeIsFree(i)) cs1.setNodeMetric(i, cs1.nodeMetric(i).scaled(1.0 / grow[i]));
    cs1.applyConstraints();
  }
}

void intersectControlSpace(AdaptiveControlSpace& cs1, const AdaptiveControlSpace& cs2, const MinimumOptions& options) {
  intersectControlSpace(cs1, cs2, cs2.controlNodes(), options);
}

double gradationSlope(double ratio) {
  require(std::isfinite(ratio) && ratio >= 1.0, ErrorCode::InvalidArgument,
          "gradation ratio dr must be finite and >= 1, got " + std::to_string(ratio));
  return 2.0 * (ratio - 1.0) / (ratio + 1.0);
}

namespace {

// Entries of the tensor M = Mt Mt of Mt entries m.
inline SymMt tensorOf(const SymMt& m) { return {m.a * m.a + m.b * m.b, m.b * (m.a + m.c), m.b * m.b + m.c * m.c}; }

// The shrink limitGradation() asks of a (sqrt(l1) - 1 for the largest eigenvalue l1 of
// Mt_a^-1 (M_i / s^2) Mt_a^-1, s = 1 + a_max |Mt_i u| = 1 + a_max d / h_i), on Mt entries
// (mi2 = tensorOf(mi)), or -1 for a zero-length edge: the cheap test in front of it.
inline double limitShrink(const SymMt& mi, const SymMt& mi2, const Vec2& u, const SymMt& a, double slope) {
  const double wx = mi.a * u.x() + mi.b * u.y(), wy = mi.b * u.x() + mi.c * u.y();
  const double len = std::sqrt(wx * wx + wy * wy);
  if (!(len > 0.0)) return -1.0;
  const double inv = 1.0 / ((a.a * a.c - a.b * a.b) * (1.0 + slope * len));
  const double ia = a.c * inv, ib = -a.b * inv, ic = a.a * inv;
  const double x00 = ia * mi2.a + ib * mi2.b, x01 = ia * mi2.b + ib * mi2.c;
  const double x10 = ib * mi2.a + ic * mi2.b, x11 = ib * mi2.b + ic * mi2.c;
  const double n00 = x00 * ia + x01 * ib, n01 = x00 * ib + x01 * ic, n11 = x10 * ib + x11 * ic;
  const double mean = 0.5 * (n00 + n11), half = 0.5 * (n00 - n11);
  return std::sqrt(std::max(mean + std::sqrt(half * half + n01 * n01), 0.0)) - 1.0;
}

}  // namespace

bool limitGradation(const Metric& mi, const Vec2& pi, Metric& mj, const Vec2& pj, double slope, double tolerance) {
  const Vec2 u = pj - pi;
  const double d = u.norm();
  if (d <= 0.0) return false;
  const double hi = mi.sizeAlong(u);
  const double s = 1.0 + slope * d / hi;  // eq. 7 at a = a_max
  // Cheap test first: mj already inside s mi when the largest eigenvalue of
  // Mt_j^-1 (M_i / s^2) Mt_j^-1 is <= 1 (no trigonometry, unlike intersect()).
  const Mat2 ij = mj.transform().inverse();
  const Mat2 q = ij * mi.tensor() * ij / (s * s);
  const double half = 0.5 * (q(0, 0) - q(1, 1)), off = 0.5 * (q(0, 1) + q(1, 0));
  const double lmax = 0.5 * (q(0, 0) + q(1, 1)) + std::sqrt(half * half + off * off);
  // sqrt(lmax) - 1: the largest relative shrink of mj's sizes the limit asks for.
  if (std::sqrt(std::max(lmax, 0.0)) - 1.0 <= tolerance) return false;
  const Metric cand = intersect(mj, mi.scaled(s));
  if (cand.transform() == mj.transform()) return false;
  mj = cand;
  return true;
}

namespace {

// Max-heap of node indices by key (ties: smaller index first) with the position of each
// node, so a node whose key changes moves in place instead of leaving a stale entry.
class NodeHeap {
 public:
  explicit NodeHeap(int n) : key_(n, 0.0), pos_(n, -1) {}
  bool empty() const { return heap_.empty(); }
  // The node pop() would return now (the heap must not be empty).
  int top() const { return heap_.front(); }
  // Inserts node i with key k, or moves it to key k when present.
  void set(int i, double k) {
    key_[i] = k;
    if (pos_[i] < 0) {
      pos_[i] = static_cast<int>(heap_.size());
      heap_.push_back(i);
    }
    down(up(pos_[i]));
  }
  // Removes and returns the top node.
  int pop() {
    const int top = heap_.front();
    pos_[top] = -1;
    const int last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) {
      heap_[0] = last;
      pos_[last] = 0;
      down(0);
    }
    return top;
  }

 private:
  bool before(int a, int b) const { return key_[a] > key_[b] || (key_[a] == key_[b] && a < b); }
  void place(int at, int i) {
    heap_[at] = i;
    pos_[i] = at;
  }
  int up(int at) {
    const int i = heap_[at];
    while (at > 0) {
      const int parent = (at - 1) / 2;
      if (!before(i, heap_[parent])) break;
      place(at, heap_[parent]);
      at = parent;
    }
    place(at, i);
    return at;
  }
  void down(int at) {
    const int i = heap_[at];
    const int size = static_cast<int>(heap_.size());
    for (;;) {
      int child = 2 * at + 1;
      if (child >= size) break;
      if (child + 1 < size && before(heap_[child + 1], heap_[child])) ++child;
      if (!before(heap_[child], i)) break;
      place(at, heap_[child]);
      at = child;
    }
    place(at, i);
  }

  std::vector<double> key_;
  std::vector<int> pos_;
  std::vector<int> heap_;
};

// Largest eigenvalue of Mt: the inverse of the smallest requested size.
inline double sizeKey(const SymMt& m) {
  const double half = 0.5 * (m.a - m.c);
  return 0.5 * (m.a + m.c) + std::sqrt(half * half + m.b * m.b);
}

// One work-set pass over the graph (start, nbr) from `seeds` (see smoothGradation);
// nodes it changes get changed[i] = 1.
int gradationWorkSet(AdaptiveControlSpace& cs, const std::vector<int>& start, const std::vector<int>& nbr,
                     const std::vector<int>& seeds, double slope, double tolerance, std::vector<char>& changed) {
  const int n = cs.nodeCount();
  // Ordered by the node's smallest requested size (smallest first, as in Dijkstra): a
  // node is mostly final when it is taken, so few nodes are re-queued.
  NodeHeap heap(n);
  for (int i : seeds) heap.set(i, sizeKey(cs.nodeMt(i)));
  int updates = 0;
  auto enqueue = [&](int j, const SymMt& mj) {
    changed[j] = 1;
    heap.set(j, sizeKey(mj));
  };
  while (!heap.empty()) {
    const int i = heap.pop();
    // The walk goes in size order, so node i and its neighbours lie anywhere in memory:
    // request their data (and the next candidate's adjacency) together instead of
    // waiting on one cache miss after another. Timing only; results are unchanged.
    for (int k = start[i]; k < start[i + 1]; ++k) {
      __builtin_prefetch(&cs.nodePosition(nbr[k]));
      __builtin_prefetch(&cs.nodeMt(nbr[k]));
    }
    if (!heap.empty()) {
      const int next = heap.top();
      __builtin_prefetch(&start[next]);
      __builtin_prefetch(&nbr[start[next]]);
      __builtin_prefetch(&cs.nodeMt(next));
      __builtin_prefetch(&cs.nodePosition(next));
    }
    const SymMt mi = cs.nodeMt(i);
    const SymMt mi2 = tensorOf(mi);
    const Metric mim = cs.nodeMetric(i);
    const Vec2 pi = cs.nodePosition(i);
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const int j = nbr[k];
      const Vec2& pj = cs.nodePosition(j);
      // Clearly within the limit (margin far above the rounding between the two
      // computations): skip; otherwise limitGradation() decides and computes, so the
      // result is the same as with limitGradation() alone.
      if (limitShrink(mi, mi2, pj - pi, cs.nodeMt(j), slope) < tolerance - 1e-12) continue;
      Metric mj = cs.nodeMetric(j);
      if (limitGradation(mim, pi, mj, pj, slope, tolerance)) {
        cs.setNodeMetric(j, mj);
        ++updates;
        enqueue(j, cs.nodeMt(j));
      }
    }
  }
  return updates;
}

// Mt of hanging node h from its masters' current values.
SymMt interpolateHanging(const AdaptiveControlSpace& cs, const AdaptiveControlSpace::HangingNode& h) {
  SymMt r{0.0, 0.0, 0.0};
  for (int j = 0; j < 3; ++j) {
    const SymMt& m = cs.nodeMt(h.masters[j]);
    r.a += h.weights[j] * m.a;
    r.b += h.weights[j] * m.b;
    r.c += h.weights[j] * m.c;
  }
  return r;
}

}  // namespace

int smoothGradation(AdaptiveControlSpace& cs, const GradationOptions& options) {
  const double slope = gradationSlope(options.ratio);
  require(options.tolerance >= 0.0, ErrorCode::InvalidArgument, "gradation tolerance must be >= 0");
  const int n = cs.nodeCount();
  const double tol = options.tolerance;
  const auto hanging =
      options.throughHangingNodes ? cs.hangingNodes() : std::vector<AdaptiveControlSpace::HangingNode>{};
  std::vector<int> start, nbr;
  cs.edgeGraph(!hanging.empty(), start, nbr);
  std::vector<int> seeds;
  for (int i = 0; i < n; ++i)
    if (!hanging.empty() || cs.nodeIsFree(i)) seeds.push_back(i);
  std::vector<char> changed(n, 0);
  int updates = gradationWorkSet(cs, start, nbr, seeds, slope, tol, changed);
  if (hanging.empty()) {
    cs.applyConstraints();
    return updates;
  }
  // Hanging nodes were smoothed like free nodes. Where smoothing moved one, its
  // positive-weight masters shrink to the smoothed value (then the interpolation is at
  // least as fine, in Mt), finest hanging nodes first so that a hanging master passes the
  // shrink on to its own masters; constraints are re-applied and the work-set restarts
  // from the hanging nodes whose value moved, the changed masters and their neighbours.
  // A round in which no hanging node moves ends with the bound holding on every side
  // edge; bilinear trees get there in a few rounds. Serendipity
  // constraints have a negative weight (and Mt interpolation is not monotone in every
  // direction), so a round cap bounds the work; at the cap, free nodes are settled on
  // their own graph (edges between free nodes then satisfy the bound; small excesses may
  // remain on a few edges at hanging nodes).
  std::vector<int> hangingOf(n, -1);
  for (size_t k = 0; k < hanging.size(); ++k) hangingOf[hanging[k].node] = static_cast<int>(k);
  std::vector<char> seeded(n, 0);
  auto seedWithNeighbours = [&](int i) {
    if (!seeded[i]) {
      seeded[i] = 1;
      seeds.push_back(i);
    }
    for (int k = start[i]; k < start[i + 1]; ++k)
      if (!seeded[nbr[k]]) {
        seeded[nbr[k]] = 1;
        seeds.push_back(nbr[k]);
      }
  };
  bool settled = false;
  std::vector<SymMt> before(hanging.size());
  for (int round = 0; round < 48; ++round) {
    // Hanging nodes moved by the work-set, finest first (max-heap on the index, which
    // follows the level); a hanging master that shrinks joins the heap, so the shrink
    // reaches free masters within the round.
    std::vector<int> dirty;
    std::vector<char> inDirty(hanging.size(), 0);
    for (int i = 0; i < n; ++i)
      if (changed[i] && hangingOf[i] >= 0) {
        dirty.push_back(hangingOf[i]);
        inDirty[hangingOf[i]] = 1;
      }
    std::fill(changed.begin(), changed.end(), 0);
    std::make_heap(dirty.begin(), dirty.end());
    std::vector<int> movedMasters;
    while (!dirty.empty()) {
      std::pop_heap(dirty.begin(), dirty.end());
      const int k = dirty.back();
      dirty.pop_back();
      const auto& h = hanging[k];
      const Metric smoothed = cs.nodeMetric(h.node);
      if (difference(toMetric(interpolateHanging(cs, h)), smoothed) <= tol) continue;
      for (int j = 0; j < 3; ++j) {
        if (h.weights[j] <= 0.0) continue;
        const int mk = h.masters[j];
        const Metric m = cs.nodeMetric(mk);
        const Metric cand = intersect(m, smoothed);
        if (difference(m, cand) <= tol) continue;
        cs.setNodeMetric(mk, cand);
        ++updates;
        movedMasters.push_back(mk);
        const int km = hangingOf[mk];
        if (km >= 0 && !inDirty[km]) {
          inDirty[km] = 1;
          dirty.push_back(km);
          std::push_heap(dirty.begin(), dirty.end());
        }
      }
    }
    // Hanging nodes take their interpolation again: those that moved (smoothed, or their
    // masters changed) must limit their neighbours and be limited by them once more.
    for (size_t k = 0; k < hanging.size(); ++k) before[k] = cs.nodeMt(hanging[k].node);
    cs.applyConstraints();
    seeds.clear();
    std::fill(seeded.begin(), seeded.end(), 0);
    for (size_t k = 0; k < hanging.size(); ++k) {
      const SymMt& now = cs.nodeMt(hanging[k].node);
      const SymMt& was = before[k];
      const double scale = std::max({std::abs(was.a), std::abs(was.b), std::abs(was.c)});
      if (std::max({std::abs(now.a - was.a), std::abs(now.b - was.b), std::abs(now.c - was.c)}) <= tol * scale)
        continue;
      const int d = hanging[k].node;
      // Finer than before: limiting its neighbours (taking it) is enough. Otherwise its
      // neighbours must limit it again too.
      const Mat2 iw = toMetric(now).transform().inverse();
      const Mat2 q = iw * toMetric(was).tensor() * iw;
      const double half = 0.5 * (q(0, 0) - q(1, 1)), off = q(0, 1);
      const bool finer = 0.5 * (q(0, 0) + q(1, 1)) + std::sqrt(half * half + off * off) <= 1.0 + tol;
      if (finer) {
        if (!seeded[d]) {
          seeded[d] = 1;
          seeds.push_back(d);
        }
      } else {
        seedWithNeighbours(d);
      }
    }
    for (int m : movedMasters) seedWithNeighbours(m);
    if (seeds.empty()) {
      settled = true;
      break;
    }
    std::sort(seeds.begin(), seeds.end());
    updates += gradationWorkSet(cs, start, nbr, seeds, slope, tol, changed);
  }
  if (!settled) {
    std::vector<int> fstart, fnbr;
    cs.edgeGraph(false, fstart, fnbr);
    seeds.clear();
    for (int i = 0; i < n; ++i)
      if (cs.nodeIsFree(i)) seeds.push_back(i);
    updates += gradationWorkSet(cs, fstart, fnbr, seeds, slope, tol, changed);
  }
  cs.applyConstraints();
  return updates;
}

Metric clampMetricSizes(const Metric& m, double hmin, double hmax) {
  const MetricSizes s = m.sizes();
  const double h1 = std::clamp(s.h1, hmin, hmax), h2 = std::clamp(s.h2, hmin, hmax);
  if (h1 == s.h1 && h2 == s.h2) return m;
  return Metric::fromSizes(s.alpha, h1, h2);
}

void clampSizes(AdaptiveControlSpace& cs, double hmin, double hmax) {
  require(std::isfinite(hmin) && hmin > 0.0 && !(hmax < hmin), ErrorCode::InvalidArgument,
          "size clamps need 0 < hmin <= hmax");
  for (int i = 0; i < cs.nodeCount(); ++i)
    if (cs.nodeIsFree(i)) cs.setNodeMetric(i, clampMetricSizes(cs.nodeMetric(i), hmin, hmax));
  cs.applyConstraints();
}

}  // namespace anisomesh

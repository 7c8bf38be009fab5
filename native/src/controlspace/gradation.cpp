// Gradation smoothing of a control space (section 2.5): the slope a_max, the pairwise rule
// limiting a neighbour's metric, the work-set propagation over the structure.
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/number_text.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"

namespace anisomesh {

double gradationSlope(double ratio) {
  require(std::isfinite(ratio) && ratio >= 1.0, ErrorCode::InvalidArgument,
          "gradation ratio dr must be finite and >= 1, got " + numberText(ratio));
  return 2.0 * (ratio - 1.0) / (ratio + 1.0);
}

namespace {

// Entries of the tensor M = Mt Mt of Mt entries m.
inline SymMt tensorOf(const SymMt& m) { return {m.a * m.a + m.b * m.b, m.b * (m.a + m.c), m.b * m.b + m.c * m.c}; }

// The entries of P M P for symmetric P and M (limitShrink's P: adj(Mt_a), scaled or not).
inline SymMt congruence(const SymMt& p, const SymMt& m) {
  const double x00 = p.a * m.a + p.b * m.b, x01 = p.a * m.b + p.b * m.c;
  const double x10 = p.b * m.a + p.c * m.b, x11 = p.b * m.b + p.c * m.c;
  return {x00 * p.a + x01 * p.b, x00 * p.b + x01 * p.c, x10 * p.b + x11 * p.c};
}

// The shrink limitGradation() asks of a (sqrt(l1) - 1 for the largest eigenvalue l1 of
// Mt_a^-1 (M_i / s^2) Mt_a^-1, s = 1 + a_max |Mt_i u| = 1 + a_max d / h_i), on Mt entries
// (mi2 = tensorOf(mi)), or -1 for a zero-length edge: the cheap test in front of it.
inline double limitShrink(const SymMt& mi, const SymMt& mi2, const Vec2& u, const SymMt& a, double slope) {
  const double wx = mi.a * u.x() + mi.b * u.y(), wy = mi.b * u.x() + mi.c * u.y();
  const double len = std::sqrt(wx * wx + wy * wy);
  if (!(len > 0.0)) return -1.0;
  const double inv = 1.0 / ((a.a * a.c - a.b * a.b) * (1.0 + slope * len));
  const SymMt n = congruence({a.c * inv, -a.b * inv, a.a * inv}, mi2);
  const double mean = 0.5 * (n.a + n.c), half = 0.5 * (n.a - n.c);
  return std::sqrt(std::max(mean + std::sqrt(half * half + n.b * n.b), 0.0)) - 1.0;
}

// Whether limitShrink(mi, mi2, u, a, slope) < limit (limit > -1), decided without its
// division and two of its three square roots where that is safe: on adj(Mt_a) instead of
// Mt_a^-1 (the largest eigenvalue l of adj M_i adj is l1 (det s)^2), against the bound
// T = ((1 + limit) det s)^2 as mean < T and half^2 + n01^2 < (T - mean)^2. The two forms
// round differently, but only next to the limit: on 2e7 random pairs (anisotropy up to
// ~1e3, a third steered to within 1e-14 of the limit) they disagreed only where the shrink
// was within 4e-14 of it, 25x inside the 1e-12 margin the caller keeps from
// limitGradation(), so the same pairs are left to it. Unusual values (a not positive
// definite, NaN, T outside [1e-150, 1e150] where squares could underflow or overflow) take
// limitShrink() itself.
inline bool shrinkBelow(const SymMt& mi, const SymMt& mi2, const Vec2& u, const SymMt& a, double slope, double limit) {
  const double wx = mi.a * u.x() + mi.b * u.y(), wy = mi.b * u.x() + mi.c * u.y();
  const double len = std::sqrt(wx * wx + wy * wy);
  if (!(len > 0.0)) return -1.0 < limit;
  const double det = a.a * a.c - a.b * a.b;
  const double bound = (1.0 + limit) * det * (1.0 + slope * len);
  const double t = bound * bound;
  if (!(det > 0.0 && t >= 1e-150 && t <= 1e150)) return limitShrink(mi, mi2, u, a, slope) < limit;
  const SymMt n = congruence({a.c, -a.b, a.a}, mi2);
  const double mean = 0.5 * (n.a + n.c), half = 0.5 * (n.a - n.c);
  const double room = t - mean;
  return room > 0.0 && half * half + n.b * n.b < room * room;
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
// node, so a node whose key changes moves in place instead of leaving a stale entry. The
// keys sit in the heap's entries (a comparison reads no other memory). (key, index) is a
// strict order, so the nodes come out in the same order however the heap was built.
class NodeHeap {
 public:
  explicit NodeHeap(int n) : pos_(n, -1) {}
  bool empty() const { return heap_.empty(); }
  // The node pop() would return now (the heap must not be empty).
  int top() const { return heap_.front().node; }
  // Inserts node i with key k, or moves it to key k when present.
  void set(int i, double k) {
    if (pos_[i] < 0) {
      pos_[i] = static_cast<int>(heap_.size());
      heap_.push_back({k, i});
    } else {
      heap_[pos_[i]].key = k;
    }
    down(up(pos_[i]));
  }
  // Inserts nodes (distinct, none present) with keys key(i) into an empty heap at once.
  template <class Key>
  void build(const std::vector<int>& nodes, Key key) {
    for (int i : nodes) {
      if (pos_[i] >= 0) {  // (a repeat: as set() would take it)
        set(i, key(i));
        continue;
      }
      pos_[i] = static_cast<int>(heap_.size());
      heap_.push_back({key(i), i});
    }
    for (int at = static_cast<int>(heap_.size()) / 2 - 1; at >= 0; --at) down(at);
  }
  // Removes and returns the top node.
  int pop() {
    const int top = heap_.front().node;
    pos_[top] = -1;
    const Entry last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) {
      heap_[0] = last;
      pos_[last.node] = 0;
      down(0);
    }
    return top;
  }

 private:
  struct Entry {
    double key;
    int node;
  };
  static bool before(const Entry& a, const Entry& b) { return a.key > b.key || (a.key == b.key && a.node < b.node); }
  void place(int at, const Entry& e) {
    heap_[at] = e;
    pos_[e.node] = at;
  }
  int up(int at) {
    const Entry e = heap_[at];
    while (at > 0) {
      const int parent = (at - 1) / 2;
      if (!before(e, heap_[parent])) break;
      place(at, heap_[parent]);
      at = parent;
    }
    place(at, e);
    return at;
  }
  void down(int at) {
    const Entry e = heap_[at];
    const int size = static_cast<int>(heap_.size());
    for (;;) {
      int child = 2 * at + 1;
      if (child >= size) break;
      if (child + 1 < size && before(heap_[child + 1], heap_[child])) ++child;
      if (!before(heap_[child], e)) break;
      place(at, heap_[child]);
      at = child;
    }
    place(at, e);
  }

  std::vector<int> pos_;
  std::vector<Entry> heap_;
};

// Largest eigenvalue of Mt: the inverse of the smallest requested size.
inline double sizeKey(const SymMt& m) {
  const double half = 0.5 * (m.a - m.c);
  return 0.5 * (m.a + m.c) + std::sqrt(half * half + m.b * m.b);
}

// Nodes a work-set pass changed: a flag per node and their list, so the rounds at hanging
// nodes cost what they change, not the node count.
struct ChangedNodes {
  explicit ChangedNodes(int n) : flag(n, 0) {}
  void add(int i) {
    if (!flag[i]) {
      flag[i] = 1;
      list.push_back(i);
    }
  }
  void clear() {
    for (int i : list) flag[i] = 0;
    list.clear();
  }
  std::vector<char> flag;
  std::vector<int> list;
};

// One work-set pass over the graph (start, nbr) from `seeds` (see smoothGradation);
// nodes it changes join `changed`. `heap` (empty, sized for the node count) is
// reused across passes: the later passes of smoothGradation() take a few nodes each, so
// allocating and clearing a node-count heap per pass would cost more than the pass.
int gradationWorkSet(AdaptiveControlSpace& cs, const std::vector<int>& start, const std::vector<int>& nbr,
                     const std::vector<int>& seeds, double slope, double tolerance, ChangedNodes& changed,
                     NodeHeap& heap) {
  // Ordered by the node's smallest requested size (smallest first, as in Dijkstra): a
  // node is mostly final when it is taken, so few nodes are re-queued.
  // At once (heapified) when no key is NaN: NaN keys are not ordered, and only the
  // one-by-one insertion gives their order as it always was.
  bool ordered = heap.empty();
  for (size_t k = 0; ordered && k < seeds.size(); ++k) ordered = !std::isnan(sizeKey(cs.nodeMt(seeds[k])));
  if (ordered)
    heap.build(seeds, [&](int i) { return sizeKey(cs.nodeMt(i)); });
  else
    for (int i : seeds) heap.set(i, sizeKey(cs.nodeMt(i)));
  int updates = 0;
  auto enqueue = [&](int j, const SymMt& mj) {
    changed.add(j);
    heap.set(j, sizeKey(mj));
  };
  while (!heap.empty()) {
    cs.refinementTick();  // cancellable: a drag's stale run stops within a few ms
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
      if (shrinkBelow(mi, mi2, pj - pi, cs.nodeMt(j), slope, tolerance - 1e-12)) continue;
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

// smoothGradation() with the work-set started from the nodes `only` holds (increasing),
// or from every node when it is null.
int smoothFrom(AdaptiveControlSpace& cs, const std::vector<int>* only, const GradationOptions& options) {
  const double slope = gradationSlope(options.ratio);
  require(options.tolerance >= 0.0, ErrorCode::InvalidArgument, "gradation tolerance must be >= 0");
  const int n = cs.nodeCount();
  const double tol = options.tolerance;
  if (only && only->empty()) {  // nothing changed: the bound still holds everywhere
    cs.applyConstraints();
    return 0;
  }
  const auto hanging =
      options.throughHangingNodes ? cs.hangingNodes() : std::vector<AdaptiveControlSpace::HangingNode>{};
  const AdaptiveControlSpace::EdgeGraph& graph = cs.edgeGraph(!hanging.empty());
  const std::vector<int>&start = graph.start, &nbr = graph.nbr;
  std::vector<int> seeds;
  if (only) {
    // The changed nodes and their neighbours: a node that grew (clampSizes) may now break
    // the bound its unchanged neighbour sets, and that neighbour must be taken to restore it.
    std::vector<char> mark(n, 0);
    for (int i : *only) {
      if (i < 0 || i >= n) continue;
      mark[i] = 1;
      for (int k = start[i]; k < start[i + 1]; ++k) mark[nbr[k]] = 1;
    }
    for (int i = 0; i < n; ++i)
      if (mark[i] && (!hanging.empty() || cs.nodeIsFree(i))) seeds.push_back(i);
  } else {
    for (int i = 0; i < n; ++i)
      if (!hanging.empty() || cs.nodeIsFree(i)) seeds.push_back(i);
  }
  ChangedNodes changed(n);
  NodeHeap heap(n);
  int updates = gradationWorkSet(cs, start, nbr, seeds, slope, tol, changed, heap);
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
  // Nodes changed since constraints were last applied (flag and list).
  std::vector<char> touched(n, 0);
  std::vector<int> touchedList;
  auto touch = [&](int i) {
    if (!touched[i]) {
      touched[i] = 1;
      touchedList.push_back(i);
    }
  };
  std::vector<AdaptiveControlSpace::RewrittenNode> rewritten;
  bool settled = false;
  for (int round = 0; round < 48; ++round) {
    // Hanging nodes moved by the work-set, finest first (max-heap on the index, which
    // follows the level); a hanging master that shrinks joins the heap, so the shrink
    // reaches free masters within the round.
    std::vector<int> dirty;
    std::vector<char> inDirty(hanging.size(), 0);
    // (Popped largest first: the order does not depend on the list's.)
    for (int i : changed.list) {
      if (hangingOf[i] >= 0) {
        dirty.push_back(hangingOf[i]);
        inDirty[hangingOf[i]] = 1;
      }
      if (round > 0) touch(i);
    }
    changed.clear();
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
        touch(mk);
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
    // After the first round only the nodes changed since the last application can move a
    // hanging node: a round costs what it changes, not the hanging-node count.
    rewritten.clear();
    if (round == 0) {
      for (const auto& h : hanging) rewritten.push_back({h.node, cs.nodeMt(h.node)});
      cs.applyConstraints();
    } else {
      cs.applyConstraintsTouched(touched, touchedList, rewritten);
    }
    for (int i : touchedList) touched[i] = 0;
    for (const auto& w : rewritten) touched[w.node] = 0;
    touchedList.clear();
    for (int i : seeds) seeded[i] = 0;  // (seeds holds every node marked)
    seeds.clear();
    for (const auto& w : rewritten) {
      const SymMt& now = cs.nodeMt(w.node);
      const SymMt& was = w.before;
      const double scale = std::max({std::abs(was.a), std::abs(was.b), std::abs(was.c)});
      if (std::max({std::abs(now.a - was.a), std::abs(now.b - was.b), std::abs(now.c - was.c)}) <= tol * scale)
        continue;
      const int d = w.node;
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
    updates += gradationWorkSet(cs, start, nbr, seeds, slope, tol, changed, heap);
  }
  if (!settled) {
    const AdaptiveControlSpace::EdgeGraph& freeGraph = cs.edgeGraph(false);
    seeds.clear();
    for (int i = 0; i < n; ++i)
      if (cs.nodeIsFree(i)) seeds.push_back(i);
    updates += gradationWorkSet(cs, freeGraph.start, freeGraph.nbr, seeds, slope, tol, changed, heap);
  }
  cs.applyConstraints();
  return updates;
}

}  // namespace

int smoothGradation(AdaptiveControlSpace& cs, const GradationOptions& options) {
  return smoothFrom(cs, nullptr, options);
}

int resmoothGradation(AdaptiveControlSpace& cs, const std::vector<int>& changed, const GradationOptions& options) {
  return smoothFrom(cs, &changed, options);
}

}  // namespace anisomesh

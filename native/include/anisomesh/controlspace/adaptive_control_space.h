#pragma once
// Common ground of the two adaptive control space structures of the paper (section 2.1):
// the balanced quadtree and the background mesh. Both store the metric transformation
// matrix Mt in control nodes and can be refined by splitting elements (quadtree leaves,
// triangles). The algorithms that build and combine control spaces (discrete and
// continuous sources, minimum, gradation smoothing; see control_space_algorithms.h) work
// on this interface only, so every one of them serves both structures.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/metric/sym_mt.h"

namespace anisomesh {

// A control node seen from outside: position, metric and the size of the smallest
// element touching it (the resolution of the structure there).
struct ControlNode {
  Vec2 position;
  Metric metric;
  double elementSize = 0.0;
};

// An element (quadtree leaf or triangle) offered to a refinement predicate.
struct ControlElement {
  int id = -1;                 // leaf cell index or triangle index
  Box2 box;                    // bounding box
  double size = 0.0;           // longest side
  int nodeCount = 0;           // 3 (triangle), 4 (bilinear leaf) or 8 (serendipity leaf)
  std::array<int, 8> nodes{};  // control nodes of the element (hanging ones included)
  int sampleCount = 0;         // interior points where the interpolation is worth checking
  std::array<Vec2, 5> samples{};
};

// The nodes and weights a structure interpolates from at one point (at most 8: a
// serendipity leaf), so that any per-node field is interpolated exactly as Mt is.
struct InterpolationStencil {
  int count = 0;
  std::array<int, 8> nodes{};
  std::array<double, 8> weights{};  // sum to 1
};

// Decides whether an element must be split.
using ElementPredicate = std::function<bool(const ControlElement&)>;
// Called after each batch of splits with the range [first, last) of the nodes it created.
using NewNodesCallback = std::function<void(int first, int last)>;

// Bounds on the work of building a control space (copied by clone()).
struct ControlSpaceLimits {
  // Node budget: refine() estimates each batch of splits first and throws
  // ElementBudgetExceeded (naming the estimate) when it would pass this many nodes.
  std::int64_t maxNodes = 6315000;  // standalone structures; pipelines set controlSpaceNodeBudget()
  // Called with 0 about every 5 ms of refinement, smoothing or source insertion work (at most
  // every 256 steps); returning false throws Cancelled.
  std::function<bool(double)> progress;
};

// The node budget derived from an element budget: a 64th of it plus 262144 (a control
// space needs far fewer nodes than the mesh has elements; the examples use at most 124k).
std::int64_t controlSpaceNodeBudget(std::int64_t maxElements);

class AdaptiveControlSpace : public ControlSpace {
 public:
  Box2 bounds() const override { return box_; }
  // Queries change no state outside refine() (and edgeGraph(), not a query).
  bool concurrentQueries() const override { return true; }

  // Number of control nodes.
  int nodeCount() const { return static_cast<int>(pos_.size()); }
  // Position of node i.
  const Vec2& nodePosition(int i) const { return pos_[i]; }
  // Metric stored in node i.
  Metric nodeMetric(int i) const { return toMetric(mt_[i]); }
  // Raw Mt entries of node i.
  const SymMt& nodeMt(int i) const { return mt_[i]; }
  // False for hanging nodes, whose value follows the coarser neighbour's interpolation.
  bool nodeIsFree(int i) const { return (flags_[i] & kDependent) == 0; }
  // False while no source has reached the node (before extrapolation).
  bool nodeIsInitialized(int i) const { return (flags_[i] & kInitialized) != 0; }
  // Sets the metric of node i and marks it initialized; call applyConstraints() after a
  // batch of changes so hanging nodes follow.
  void setNodeMetric(int i, const Metric& m) {
    mt_[i] = toSymMt(m);
    flags_[i] |= kInitialized;
  }
  // Marks node i as not yet reached by any source (its value is a placeholder).
  void clearNodeInitialized(int i) { flags_[i] &= static_cast<std::uint8_t>(~kInitialized); }

  // Recomputes hanging nodes from their masters (no-op for structures without them).
  virtual void applyConstraints() {}
  // A hanging node rewritten by applyConstraintsTouched() and its Mt before.
  struct RewrittenNode {
    int node;
    SymMt before;
  };
  // applyConstraints() for the hanging nodes whose node or a master is flagged in `touched`
  // (flags grow by the nodes rewritten, so dependents follow); the same values when only
  // the flagged nodes changed since the last application. `touchedList` holds every node
  // flagged on entry (once each). Appends the rewritten nodes, in constraint order.
  virtual void applyConstraintsTouched(std::vector<char>& touched, const std::vector<int>& touchedList,
                                       std::vector<RewrittenNode>& rewritten) {
    (void)touched;
    (void)touchedList;
    (void)rewritten;
  }
  // Pairs (i < j) of free nodes adjacent along the structure's edges, sorted: the graph
  // of gradation smoothing and extrapolation.
  std::vector<std::array<int, 2>> controlEdges() const { return sortedEdges(false); }
  // Pairs (i < j) of nodes adjacent along element sides, hanging nodes included, sorted
  // (the edges of the structure as drawn; equals controlEdges() without hanging nodes).
  std::vector<std::array<int, 2>> structureEdges() const { return sortedEdges(true); }
  // The same pairs (i < j) unsorted, possibly repeated: controlEdges() (structure false)
  // or structureEdges() (true) before sorting.
  virtual std::vector<std::array<int, 2>> rawEdges(bool structure) const = 0;
  // Adjacency (CSR) of controlEdges() or structureEdges(): the neighbours of node i are
  // nbr[start[i]] .. nbr[start[i + 1] - 1], increasing (no global sort of the edges).
  struct EdgeGraph {
    std::vector<int> start, nbr;
  };
  // The graph of controlEdges() (structure false) or structureEdges() (true), built once and
  // kept (clones share it) until the topology changes: every split adds a node, so a
  // re-smoothing after sources that split nothing (a dragged source) does not rebuild it.
  // Not for concurrent calls on one structure (it fills the cache).
  const EdgeGraph& edgeGraph(bool structure) const;
  // A hanging node: Mt(node) = sum_k weights[k] Mt(masters[k]).
  struct HangingNode {
    int node;
    std::array<int, 3> masters;
    std::array<double, 3> weights;
  };
  // Hanging nodes in evaluation order (none for a conforming structure).
  virtual std::vector<HangingNode> hangingNodes() const { return {}; }
  // Number of elements (quadtree leaves or triangles).
  virtual int elementCount() const = 0;
  // Elements for display: corner nodes of every leaf (4, counter-clockwise) or triangle (3).
  virtual std::vector<std::vector<int>> elementNodes() const = 0;
  // Splits elements while pred holds (each split keeps the structure valid: balanced
  // quadtree, conforming triangulation); new nodes take the interpolated metric and then
  // onNewNodes may overwrite free ones. Elements at the minimum size are never split.
  virtual void refine(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) = 0;
  // As refine, but pred may be called from several threads at once (parallel.h) and in any
  // order: pred must only read (this structure's queries and its own pure functions). The
  // same result as refine for any thread count. By default it is refine.
  virtual void refineConcurrently(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) {
    refine(pred, onNewNodes);
  }
  // As refine, for a pred that is false on every element whose box meets none of the
  // closed boxes `near`: the first pass may offer only the elements that meet one (a dragged
  // source's few leaves instead of every leaf). The same result as refine.
  virtual void refineNear(const std::vector<Box2>& near, const ElementPredicate& pred,
                          const NewNodesCallback& onNewNodes) {
    (void)near;
    refine(pred, onNewNodes);
  }
  // The metric at sample k of element e (an element of this structure as refine() passes
  // it): metricAt(e.samples[k]) by default; a structure whose field is continuous across
  // elements answers from e itself, without locating the point.
  virtual Metric elementSampleMetric(const ControlElement& e, int k) const { return metricAt(e.samples[size_t(k)]); }
  // Size of the smallest element touching each node.
  virtual std::vector<double> nodeElementSizes() const = 0;
  // The nodes and weights metricAt(p) interpolates Mt from (section 4.3 interpolates the
  // parameterization matrix Mp "in precisely the same way").
  virtual InterpolationStencil stencilAt(const Vec2& p) const = 0;
  // Smallest element size the structure may reach (its maximum depth).
  virtual double minElementSize() const = 0;
  // "quadtree" or "background".
  virtual const char* kindName() const = 0;
  // A deep copy (the minimum keeps the original field while it refines).
  virtual std::unique_ptr<AdaptiveControlSpace> clone() const = 0;
  // Makes this structure a copy of `other` in the storage it holds (vectors keep their
  // capacity: no fresh memory for a structure of about the same size), when both are of
  // the same kind; false (nothing changed) otherwise.
  virtual bool assignFrom(const AdaptiveControlSpace& other) {
    (void)other;
    return false;
  }

  // The node values and flags at one moment (nodesChangedSince() compares against it).
  struct NodeState {
    std::vector<SymMt> mt;
    std::vector<std::uint8_t> flags;
  };
  // A copy of the node values and flags now.
  NodeState nodeState() const { return {mt_, flags_}; }
  // Nodes (increasing) whose Mt bits or flags differ from `before`, and every node added
  // since (structures only append nodes): what a later resmoothGradation() starts from.
  std::vector<int> nodesChangedSince(const NodeState& before) const;
  // The same against the nodes of `before` (a structure this one was copied from), without
  // a copy of its values.
  std::vector<int> nodesChangedSince(const AdaptiveControlSpace& before) const;

  // All nodes with their metrics and local element sizes (free nodes only: hanging ones
  // carry no information of their own). Used as discrete sources by the minimum.
  std::vector<ControlNode> controlNodes() const;
  // Bounds on refinement (node budget, progress); refine() honours them.
  void setLimits(ControlSpaceLimits limits) { limits_ = std::move(limits); }
  const ControlSpaceLimits& limits() const { return limits_; }
  // Throws ElementBudgetExceeded when splits more splits, each adding about nodesPerSplit
  // nodes, would take the node count past limits().maxNodes (estimated before the work).
  void checkRefinementEstimate(std::int64_t splits, double nodesPerSplit) const;
  // Reports progress about every 5 ms (cheap to call per element or node: a counter, then a
  // clock read every 256 calls); throws Cancelled when the callback returns false.
  void refinementTick() const;

 private:
  std::vector<std::array<int, 2>> sortedEdges(bool structure) const;

 protected:
  static constexpr std::uint8_t kInitialized = 1;
  static constexpr std::uint8_t kDependent = 2;

  // Bytes held by the kept edge graphs (they stay with the structure: memoryBytes() counts them).
  size_t edgeGraphBytes() const {
    size_t bytes = 0;
    for (const auto& g : graphs_)
      if (g) bytes += (g->start.capacity() + g->nbr.capacity()) * sizeof(int);
    return bytes;
  }
  // Appends a node; returns its index. (Every change of topology appends nodes: the
  // cached edge graphs go.)
  int addNode(const Vec2& p, const SymMt& mt, bool initialized) {
    graphs_[0].reset();
    graphs_[1].reset();
    pos_.push_back(p);
    mt_.push_back(mt);
    flags_.push_back(initialized ? kInitialized : 0);
    return static_cast<int>(pos_.size()) - 1;
  }

  Box2 box_;
  std::vector<Vec2> pos_;
  std::vector<SymMt> mt_;
  std::vector<std::uint8_t> flags_;
  ControlSpaceLimits limits_;
  // edgeGraph(false), edgeGraph(true) while the topology stays (immutable: clones share them).
  mutable std::array<std::shared_ptr<const EdgeGraph>, 2> graphs_;
  mutable std::uint32_t ticks_ = 0;
  mutable std::int64_t lastTickNs_ = 0;
};

}  // namespace anisomesh

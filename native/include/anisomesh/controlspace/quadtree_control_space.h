#pragma once
// Adaptive balanced quadtree control space (section 2.1, fig. 1a; interpolation section
// 4.1, eq. 10, Table 1). Control nodes sit at leaf corners (and, for the quadratic
// "serendipity" interpolation, at leaf mid-edges) and are shared between leaves.
// Neighbouring leaves (sharing an edge piece) differ by one level at most after every
// operation. Nodes on the finer side of a level jump that are not nodes of the coarser
// leaf ("hanging" nodes) are not free: their value is the coarser leaf's interpolation,
// so the interpolated field is continuous.
//
// Layout: cells in flat arrays (child index, node indices), nodes addressed by integer
// lattice coordinates of resolution 2^(maxLevel+1) per axis, so a query descends by
// integer bit tests from a grid of main-level cells, without allocation or virtual calls.
//
// Threads: metricAt/mtAt/locate* only read, so concurrent queries are safe; building
// operations (refine, set*, the algorithms) need exclusive access.
#include <cstdint>
#include <optional>
#include <vector>

#include "anisomesh/controlspace/adaptive_control_space.h"

namespace anisomesh {

enum class QuadtreeInterpolation {
  Bilinear,     // 4 corner nodes (Table 1, linear)
  Serendipity,  // 8 nodes: corners and mid-edges (Table 1, quadratic)
};

struct QuadtreeOptions {
  int initialLevel = 2;  // main-level grid: 2^initialLevel cells per side
  int maxLevel = 14;     // deepest leaf level (at most 24)
  QuadtreeInterpolation interpolation = QuadtreeInterpolation::Bilinear;
  // Metric of every node at creation; when absent the nodes start uninitialized (holding
  // the isotropic metric of the box diagonal as a placeholder) until sources reach them.
  std::optional<Metric> initialMetric;
};

class QuadtreeControlSpace : public AdaptiveControlSpace {
 public:
  // Builds the main-level grid over box. Throws InvalidDomain for an empty, inverted or
  // non-finite box, InvalidArgument for levels out of range.
  explicit QuadtreeControlSpace(const Box2& box, const QuadtreeOptions& options = {});

  // Interpolated metric (eq. 10); points outside the box are clamped onto it.
  Metric metricAt(const Vec2& p) const override;
  // Interpolated Mt entries at p (the allocation-free core of metricAt).
  SymMt mtAt(const Vec2& p) const;
  // Index of the leaf cell containing p (clamped onto the box).
  int locateLeaf(const Vec2& p) const;
  InterpolationStencil stencilAt(const Vec2& p) const override;

  void applyConstraints() override;
  void applyConstraintsTouched(std::vector<char>& touched, const std::vector<int>& touchedList,
                               std::vector<RewrittenNode>& rewritten) override;
  std::vector<std::array<int, 2>> rawEdges(bool structure) const override;
  std::vector<HangingNode> hangingNodes() const override;
  int elementCount() const override { return leafCount_; }
  std::vector<std::vector<int>> elementNodes() const override;
  void refine(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) override;
  // Each batch's leaves judged in parallel chunks (pred only reads); the same splits.
  void refineConcurrently(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) override;
  void refineNear(const std::vector<Box2>& near, const ElementPredicate& pred,
                  const NewNodesCallback& onNewNodes) override;
  std::vector<double> nodeElementSizes() const override;
  double minElementSize() const override;
  const char* kindName() const override { return "quadtree"; }
  std::unique_ptr<AdaptiveControlSpace> clone() const override { return std::make_unique<QuadtreeControlSpace>(*this); }
  bool assignFrom(const AdaptiveControlSpace& other) override {
    const auto* q = dynamic_cast<const QuadtreeControlSpace*>(&other);
    if (q && q != this) *this = *q;
    return q != nullptr;
  }

  // Splits the leaf cell (first splitting coarser neighbours so balance holds).
  void splitLeaf(int cell);
  // Splits leaves whose nodes differ (difference() between any two) by more than
  // threshold, recursively, down to maxLevel.
  void refineByDifference(double threshold);

  // Interpolation scheme chosen at construction.
  QuadtreeInterpolation interpolation() const { return interp_; }
  const QuadtreeOptions& options() const { return options_; }
  // Cells (internal and leaves) and their properties.
  int cellCount() const { return static_cast<int>(child_.size()); }
  bool isLeaf(int cell) const { return child_[cell] < 0; }
  // First of the four children of an internal cell (lo-left, lo-right, hi-left, hi-right,
  // consecutive), -1 for a leaf.
  int firstChild(int cell) const { return child_[cell]; }
  int cellLevel(int cell) const { return level_[cell]; }
  Box2 cellBox(int cell) const;
  // Node indices of a leaf: 4 corners P0..P3 (counter-clockwise from lo), then for
  // serendipity the mid-edge nodes P4..P7 (Table 1 numbering).
  const int* leafNodes(int cell) const { return &cellNodes_[static_cast<size_t>(cell) * nodesPerLeaf_]; }
  int nodesPerLeaf() const { return nodesPerLeaf_; }
  // Leaf cell indices in increasing order.
  std::vector<int> leaves() const;
  // The leaves whose boxes meet one of the closed boxes `near`, in increasing order.
  std::vector<int> leavesNear(const std::vector<Box2>& near) const;
  // True when no two edge-neighbouring leaves differ by more than one level.
  bool isBalanced() const;
  // Number of bytes held by the structure (cells, nodes, lookup tables).
  size_t memoryBytes() const;

 private:
  struct Constraint {
    int node;
    int level;
    int master[3];
    double weight[3];
  };

  int latticeSize() const { return 1 << bits_; }
  int cellSpan(int level) const { return 1 << (bits_ - level); }
  // Leaf containing lattice unit cell (x, y), descending no deeper than maxDepth.
  int descend(int x, int y, int maxDepth) const;
  // Node at lattice point (x, y), or -1.
  int findNode(int x, int y) const;
  int findOrCreateNode(int x, int y, int parentCell, bool& created);
  // Leaf holding p and p's local coordinates (eta, xi) in it.
  int locateInLeaf(const Vec2& p, double& e, double& x) const;
  // Interpolation inside a cell at local coordinates (eta, xi) in [0, 1].
  SymMt interpolateInCell(int cell, double eta, double xi) const;
  void growMap();
  void splitLeafImpl(int cell);
  // refine() with its first pass over the leaves `work` (increasing); readOnly: pred may
  // judge a batch's leaves concurrently (refineConcurrently).
  void refineFrom(std::vector<int> work, const ElementPredicate& pred, const NewNodesCallback& onNewNodes,
                  bool readOnly = false);
  void rebuildConstraints() const;
  // Mt of constraint k's hanging node from its masters (initialized once they all are).
  void applyConstraint(const Constraint& k);
  ControlElement elementOf(int cell) const;

  QuadtreeOptions options_;
  QuadtreeInterpolation interp_;
  int nodesPerLeaf_;
  int bits_;        // lattice resolution 2^bits_
  int rootLevel_;   // level of the main-level grid
  int rootSide_;    // 2^rootLevel_
  Vec2 scale_;      // lattice units per length unit
  Vec2 cellScale_;  // length units per lattice unit
  double latticeMax_;

  std::vector<std::int32_t> child_;  // first child (4 consecutive) or -1 for a leaf
  std::vector<std::uint8_t> level_;
  std::vector<std::int32_t> ix_, iy_;    // lattice coordinates of the cell's lo corner
  std::vector<std::int32_t> cellNodes_;  // nodesPerLeaf_ entries per cell
  std::vector<std::int32_t> rootGrid_;   // main-level cells, row-major
  int leafCount_ = 0;

  // Open-addressing map lattice point -> node index.
  std::vector<std::uint64_t> mapKeys_;
  std::vector<std::int32_t> mapVals_;
  size_t mapUsed_ = 0;

  mutable std::vector<Constraint> constraints_;
  mutable bool constraintsDirty_ = true;
  // Every hanging master precedes its dependents in constraints_ (one pass settles all).
  mutable bool constraintsOrdered_ = true;
  // Node -> indices of the constraints that read it (as node or master), CSR, built on
  // demand for constraints_ (cleared when they are rebuilt); scratch flags per constraint.
  mutable std::vector<std::int32_t> readerStart_, readers_;
  std::vector<char> constraintQueued_;
};

}  // namespace anisomesh

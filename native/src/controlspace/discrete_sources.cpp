// Discrete metric sources inserted into a control space (section 2.2: points, segments,
// curves with a radius of influence and distance weights).
#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"
#include "bucket_grid.h"

namespace anisomesh {

using controlspace_internal::BucketGrid;
using controlspace_internal::pieceBox;
using controlspace_internal::pointBox;

namespace {

// Step (b)'s rule for one piece: a node at distance d <= limit takes the piece's metric with
// the weight 1 / t^2, t = max(d - radius, 0) + soft (soft: a quarter of the piece's reach).
struct PieceWeight {
  double radius, soft, limit;
  SymMt m;
  PieceWeight(const SourcePiece& p, double minSize) {
    const double reach = std::max(p.targetSize, minSize);
    radius = p.radius;
    soft = 0.25 * reach;
    limit = p.radius + reach;
    m = toSymMt(p.metric);
  }
  // Adds the piece, at distance d from the node, to the node's sums.
  void add(double d, SymMt& sum, double& wsum) const {
    const double t = std::max(d - radius, 0.0) + soft;
    const double w = 1.0 / (t * t);
    sum.a += w * m.a;
    sum.b += w * m.b;
    sum.c += w * m.c;
    wsum += w;
  }
};

// The distance from a point piece (a == b) to q, as distanceToPiece() computes it.
inline double pointDistance(const SourcePiece& p, const Vec2& q) {
  const double dx = p.a.x() - q.x(), dy = p.a.y() - q.y();
  return std::sqrt(dx * dx + dy * dy);
}

// Node i takes the weighted average of the pieces reaching it (intersected with its value
// when it has one); nothing when none reached it.
void setWeightedAverage(AdaptiveControlSpace& cs, int i, const SymMt& sum, double wsum) {
  if (wsum <= 0.0) return;
  const SymMt avg{sum.a / wsum, sum.b / wsum, sum.c / wsum};
  const Metric m = toMetric(avg);
  cs.setNodeMetric(i, cs.nodeIsInitialized(i) ? intersect(cs.nodeMetric(i), m) : m);
}

// Step (b) of insertSources() for a few pieces (a dragged source): every free node in turn
// takes the pieces that reach it, in their order, summed as the binned pass sums them (the
// same weights, the same order: the same bits), without per-node arrays (a drag's
// structure has tens of thousands of nodes, and the source reaches a few of them).
void insertFewPieces(AdaptiveControlSpace& cs, const std::vector<SourcePiece>& pieces, double minSize) {
  std::vector<PieceWeight> weights;
  weights.reserve(pieces.size());
  for (const SourcePiece& p : pieces) weights.emplace_back(p, minSize);
  const int n = cs.nodeCount();
  for (int i = 0; i < n; ++i) {
    cs.refinementTick();
    if (!cs.nodeIsFree(i)) continue;
    const Vec2& q = cs.nodePosition(i);
    SymMt sum{0.0, 0.0, 0.0};
    double wsum = 0.0;
    for (size_t k = 0; k < pieces.size(); ++k) {
      const SourcePiece& p = pieces[k];
      const double d = p.a == p.b ? pointDistance(p, q) : distanceToPiece(p, q);
      if (!(d > weights[k].limit)) weights[k].add(d, sum, wsum);
    }
    setWeightedAverage(cs, i, sum, wsum);
  }
}

}  // namespace

void insertSources(AdaptiveControlSpace& cs, const std::vector<MetricSource>& sources,
                   const DiscreteInsertionOptions& options) {
  const Box2 box = cs.bounds();
  const std::vector<SourcePiece> pieces = sourcePieces(sources, box, options.source);
  if (pieces.empty()) return;        // nothing inside the domain: no-op
  constexpr size_t kScanPieces = 4;  // up to this many pieces, no binning (a dragged source)

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
    const ElementPredicate nearPieces = [&](const ControlElement& e) {
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
    };
    // A few pieces (a dragged source): only the elements near them are offered.
    if (pieces.size() <= kScanPieces)
      cs.refineNear(boxes, nearPieces, nullptr);
    else
      cs.refine(nearPieces, nullptr);
  }

  // (b) Weighted average of the sources reaching each free node. Free nodes are binned,
  // and their positions and sums kept in bin order (contiguous scans); every node still
  // accumulates its sources in their order. A few pieces (a dragged source) scan every
  // free node instead (insertFewPieces): binning them would cost more than the scan, and
  // each node gets the same sources (a point lies in one bin, and the distance test
  // decides) in the same order.
  const int n = cs.nodeCount();
  const double minSize = cs.minElementSize();
  const Metric fallback =
      options.fallbackMetric ? *options.fallbackMetric : Metric::isotropic(0.25 * box.size().norm());
  if (pieces.size() <= kScanPieces) {
    insertFewPieces(cs, pieces, minSize);
    extrapolateMetric(cs, fallback);  // (c) below
    return;
  }
  std::vector<int> freeNodes;
  freeNodes.reserve(n);
  for (int i = 0; i < n; ++i)
    if (cs.nodeIsFree(i)) freeNodes.push_back(i);
  std::vector<Box2> nodeBoxes;
  nodeBoxes.reserve(freeNodes.size());
  for (int i : freeNodes) nodeBoxes.push_back(pointBox(cs.nodePosition(i), 0.0));
  const BucketGrid nodeGrid(box, nodeBoxes);
  std::vector<int> slotNode;  // the free node of each slot (bin order)
  slotNode.reserve(nodeGrid.items().size());
  for (int k : nodeGrid.items()) slotNode.push_back(freeNodes[k]);
  const size_t slots = slotNode.size();
  std::vector<Vec2> slotPos(slots);
  for (size_t k = 0; k < slots; ++k) slotPos[k] = cs.nodePosition(slotNode[k]);
  std::vector<SymMt> sum(slots, SymMt{0.0, 0.0, 0.0});
  std::vector<double> wsum(slots, 0.0);
  for (const SourcePiece& p : pieces) {
    cs.refinementTick();  // cancellable between pieces
    const PieceWeight pw(p, minSize);
    // The slots within reach, by the piece's distance (chosen once per piece).
    auto addWithin = [&](auto&& distance) {
      nodeGrid.forSlots(pieceBox(p, pw.limit), [&](int k) {
        const double d = distance(slotPos[k]);
        if (!(d > pw.limit)) pw.add(d, sum[k], wsum[k]);
      });
    };
    if (p.a == p.b)
      addWithin([&](const Vec2& q) { return pointDistance(p, q); });
    else
      addWithin([&](const Vec2& q) { return distanceToPiece(p, q); });
  }
  for (size_t k = 0; k < slots; ++k) {
    cs.refinementTick();
    setWeightedAverage(cs, slotNode[k], sum[k], wsum[k]);
  }

  // (c) Extrapolation into the nodes no source reached.
  extrapolateMetric(cs, fallback);
}

}  // namespace anisomesh

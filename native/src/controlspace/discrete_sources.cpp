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

// Step (b) of insertSources() for a few pieces (a dragged source): every free node in turn
// takes the pieces that reach it, in their order, summed as the binned pass sums them (the
// same weights, the same order: the same bits), without per-node arrays (a drag's
// structure has tens of thousands of nodes, and the source reaches a few of them).
void insertFewPieces(AdaptiveControlSpace& cs, const std::vector<SourcePiece>& pieces, double minSize) {
  struct Reach {
    double soft, limit;
    SymMt m;
  };
  std::vector<Reach> reach;
  reach.reserve(pieces.size());
  for (const SourcePiece& p : pieces) {
    const double r = std::max(p.targetSize, minSize);
    reach.push_back({0.25 * r, p.radius + r, toSymMt(p.metric)});
  }
  const int n = cs.nodeCount();
  for (int i = 0; i < n; ++i) {
    cs.refinementTick();
    if (!cs.nodeIsFree(i)) continue;
    const Vec2& q = cs.nodePosition(i);
    SymMt sum{0.0, 0.0, 0.0};
    double wsum = 0.0;
    for (size_t k = 0; k < pieces.size(); ++k) {
      const SourcePiece& p = pieces[k];
      double d;
      if (p.a == p.b) {  // a point: the distance as distanceToPiece() computes it
        const double dx = p.a.x() - q.x(), dy = p.a.y() - q.y();
        d = std::sqrt(dx * dx + dy * dy);
      } else {
        d = distanceToPiece(p, q);
      }
      const Reach& r = reach[k];
      if (d > r.limit) continue;
      const double t = std::max(d - p.radius, 0.0) + r.soft;
      const double w = 1.0 / (t * t);
      sum.a += w * r.m.a;
      sum.b += w * r.m.b;
      sum.c += w * r.m.c;
      wsum += w;
    }
    if (wsum <= 0.0) continue;
    const SymMt avg{sum.a / wsum, sum.b / wsum, sum.c / wsum};
    const Metric m = toMetric(avg);
    cs.setNodeMetric(i, cs.nodeIsInitialized(i) ? intersect(cs.nodeMetric(i), m) : m);
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
  // Calls fn(slot) for the slots that may lie in b.
  auto forSlots = [&](const Box2& b, auto&& fn) { return nodeGrid.forSlots(b, fn); };
  std::vector<Vec2> slotPos(slots);
  for (size_t k = 0; k < slots; ++k) slotPos[k] = cs.nodePosition(slotNode[k]);
  std::vector<SymMt> sum(slots, SymMt{0.0, 0.0, 0.0});
  std::vector<double> wsum(slots, 0.0);
  for (const SourcePiece& p : pieces) {
    cs.refinementTick();  // cancellable between pieces
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
      forSlots(pieceBox(p, limit), [&](int k) {
        const double dx = p.a.x() - slotPos[k].x(), dy = p.a.y() - slotPos[k].y();
        const double d = std::sqrt(dx * dx + dy * dy);
        if (!(d > limit)) add(k, d);
      });
    } else {
      forSlots(pieceBox(p, limit), [&](int k) {
        const double d = distanceToPiece(p, slotPos[k]);
        if (!(d > limit)) add(k, d);
      });
    }
  }
  for (size_t k = 0; k < slots; ++k) {
    cs.refinementTick();
    if (wsum[k] <= 0.0) continue;
    const int i = slotNode[k];
    const SymMt avg{sum[k].a / wsum[k], sum[k].b / wsum[k], sum[k].c / wsum[k]};
    const Metric m = toMetric(avg);
    cs.setNodeMetric(i, cs.nodeIsInitialized(i) ? intersect(cs.nodeMetric(i), m) : m);
  }

  // (c) Extrapolation into the nodes no source reached.
  extrapolateMetric(cs, fallback);
}

}  // namespace anisomesh

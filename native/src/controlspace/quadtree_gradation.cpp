// Section 2.5.2 upward/downward quadtree traversal (see quadtree_gradation.h).
#include "anisomesh/controlspace/quadtree_gradation.h"

#include <algorithm>
#include <vector>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

struct TreeSmoother {
  QuadtreeControlSpace& cs;
  double slope, tolerance;
  int updates = 0;
  std::vector<int> nodes;  // scratch: the distinct nodes of one cell's children

  // Pairwise rule (eqs. 8, 9) both ways between nodes a and b.
  void adjust(int a, int b) {
    if (a == b) return;
    const Vec2 pa = cs.nodePosition(a), pb = cs.nodePosition(b);
    Metric ma = cs.nodeMetric(a), mb = cs.nodeMetric(b);
    if (cs.nodeIsFree(b) && limitGradation(ma, pa, mb, pb, slope, tolerance)) {
      cs.setNodeMetric(b, mb);
      ++updates;
    }
    if (cs.nodeIsFree(a) && limitGradation(mb, pb, ma, pa, slope, tolerance)) {
      cs.setNodeMetric(a, ma);
      ++updates;
    }
  }

  // Every two distinct nodes of the children of internal cell c.
  void adjustCell(int c) {
    nodes.clear();
    const int first = cs.firstChild(c);
    for (int k = 0; k < 4; ++k) {
      const int* nd = cs.leafNodes(first + k);
      nodes.insert(nodes.end(), nd, nd + cs.nodesPerLeaf());
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (size_t i = 0; i < nodes.size(); ++i)
      for (size_t j = i + 1; j < nodes.size(); ++j) adjust(nodes[i], nodes[j]);
  }

  void up(int c) {
    if (cs.isLeaf(c)) return;
    const int first = cs.firstChild(c);
    for (int k = 0; k < 4; ++k) up(first + k);
    adjustCell(c);
  }

  void down(int c) {
    if (cs.isLeaf(c)) return;
    adjustCell(c);
    const int first = cs.firstChild(c);
    for (int k = 0; k < 4; ++k) down(first + k);
  }

  // Main level: corners of each main cell with each other, a sweep each way.
  void mainLevel(const std::vector<int>& roots) {
    auto cellCorners = [&](int c) {
      const int* nd = cs.leafNodes(c);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) adjust(nd[i], nd[j]);
    };
    for (int c : roots) cellCorners(c);
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) cellCorners(*it);
  }
};

}  // namespace

int smoothGradationUpDown(QuadtreeControlSpace& cs, const TreeGradationOptions& options) {
  const double slope = gradationSlope(options.ratio);
  require(options.tolerance >= 0.0, ErrorCode::InvalidArgument, "gradation tolerance must be >= 0");
  require(options.passes >= 1, ErrorCode::InvalidArgument, "gradation passes must be >= 1");
  std::vector<int> roots;
  int rootLevel = 1 << 30;
  for (int c = 0; c < cs.cellCount(); ++c) rootLevel = std::min(rootLevel, cs.cellLevel(c));
  for (int c = 0; c < cs.cellCount(); ++c)
    if (cs.cellLevel(c) == rootLevel) roots.push_back(c);
  TreeSmoother s{cs, slope, options.tolerance, 0, {}};
  for (int pass = 0; pass < options.passes; ++pass) {
    for (int c : roots) s.up(c);
    s.mainLevel(roots);
    for (int c : roots) s.down(c);
  }
  cs.applyConstraints();
  return s.updates;
}

}  // namespace anisomesh

// Extrapolation of the metric to the control nodes no source reached (section 3.1).
#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"

namespace anisomesh {

int extrapolateMetric(AdaptiveControlSpace& cs, const Metric& fallback) {
  const int n = cs.nodeCount();
  std::vector<char> known(n, 0);
  bool any = false, unknown = false;
  for (int i = 0; i < n; ++i) {
    known[i] = cs.nodeIsFree(i) && cs.nodeIsInitialized(i);
    any = any || known[i];
    unknown = unknown || (!known[i] && cs.nodeIsFree(i));
  }
  int filled = 0;
  // (Every free node known, as after sources that reach the whole structure: nothing to
  // fill, so the edge graph, a fifth of a surface drag's gradation cost, is not built.)
  if (any && unknown) {
    const AdaptiveControlSpace::EdgeGraph& graph = cs.edgeGraph(false);
    const std::vector<int>&start = graph.start, &nbr = graph.nbr;
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

}  // namespace anisomesh

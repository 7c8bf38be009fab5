// The graph of an adaptive control space (structure edges and neighbours of its nodes) and
// its nodes seen from outside.
#include "anisomesh/controlspace/control_space_algorithms.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"

namespace anisomesh {

std::vector<std::array<int, 2>> AdaptiveControlSpace::sortedEdges(bool structure) const {
  std::vector<std::array<int, 2>> edges = rawEdges(structure);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

const AdaptiveControlSpace::EdgeGraph& AdaptiveControlSpace::edgeGraph(bool structure) const {
  std::shared_ptr<const EdgeGraph>& kept = graphs_[structure ? 1 : 0];
  if (kept) return *kept;
  auto graph = std::make_shared<EdgeGraph>();
  std::vector<int>& start = graph->start;
  std::vector<int>& nbr = graph->nbr;
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
  kept = std::move(graph);
  return *kept;
}

namespace {

std::uint64_t bitsOf(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Bits, not values: a NaN that stayed NaN is the same, -0 against 0 is a change.
bool sameBits(const SymMt& x, const SymMt& y) {
  return bitsOf(x.a) == bitsOf(y.a) && bitsOf(x.b) == bitsOf(y.b) && bitsOf(x.c) == bitsOf(y.c);
}

// Nodes (increasing) of now (mt, flags) whose values differ from those of before, and every
// node past before's.
std::vector<int> changedNodes(const std::vector<SymMt>& mt, const std::vector<std::uint8_t>& flags,
                              const std::vector<SymMt>& beforeMt, const std::vector<std::uint8_t>& beforeFlags) {
  std::vector<int> out;
  const int n = static_cast<int>(mt.size());
  const int kept = static_cast<int>(std::min({beforeMt.size(), beforeFlags.size(), mt.size()}));
  for (int i = 0; i < kept; ++i)
    if (flags[i] != beforeFlags[i] || !sameBits(mt[i], beforeMt[i])) out.push_back(i);
  for (int i = kept; i < n; ++i) out.push_back(i);
  return out;
}

}  // namespace

std::vector<int> AdaptiveControlSpace::nodesChangedSince(const NodeState& before) const {
  return changedNodes(mt_, flags_, before.mt, before.flags);
}

std::vector<int> AdaptiveControlSpace::nodesChangedSince(const AdaptiveControlSpace& before) const {
  return changedNodes(mt_, flags_, before.mt_, before.flags_);
}

std::vector<ControlNode> AdaptiveControlSpace::controlNodes() const {
  const std::vector<double> sizes = nodeElementSizes();
  std::vector<ControlNode> out;
  out.reserve(nodeCount());
  for (int i = 0; i < nodeCount(); ++i)
    if (nodeIsFree(i)) out.push_back({pos_[i], nodeMetric(i), sizes[i]});
  return out;
}

}  // namespace anisomesh

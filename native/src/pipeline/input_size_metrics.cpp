// Sizes for remeshing without a solution file (see input_size_metrics.h).
#include "anisomesh/pipeline/input_size_metrics.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "anisomesh/core/error.h"

namespace anisomesh {

std::vector<Metric> edgeLengthMetrics(const Mesh& mesh) {
  const int n = mesh.vertexCount();
  std::vector<std::pair<int, int>> edges;
  auto add = [&](int a, int b) {
    require(a >= 0 && a < n && b >= 0 && b < n, ErrorCode::InvalidArgument, "mesh: vertex index out of range");
    edges.emplace_back(std::min(a, b), std::max(a, b));
  };
  for (const auto& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) add(t[i], t[(i + 1) % 3]);
  for (const auto& q : mesh.quads)
    for (int i = 0; i < 4; ++i) add(q[i], q[(i + 1) % 4]);
  for (const auto& e : mesh.edges) add(e[0], e[1]);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> sum(n, 0.0);
  std::vector<int> count(n, 0);
  for (const auto& [a, b] : edges) {
    const double len = (mesh.points[a] - mesh.points[b]).norm();
    sum[a] += len;
    sum[b] += len;
    ++count[a];
    ++count[b];
  }
  std::vector<Metric> metrics;
  metrics.reserve(n);
  for (int v = 0; v < n; ++v) {
    require(count[v] > 0, ErrorCode::InvalidArgument,
            "vertex " + std::to_string(v + 1) + " is on no edge: no size to take from the input mesh");
    metrics.push_back(Metric::isotropic(sum[v] / count[v]));
  }
  return metrics;
}

std::vector<Metric> uniformMetrics(const Mesh& mesh, double h) {
  return std::vector<Metric>(mesh.vertexCount(), Metric::isotropic(h));
}

}  // namespace anisomesh

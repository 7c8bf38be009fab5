// The all-quad split, one function for planar and surface meshes (the boundary points come
// from the contour curves so that curved boundaries stay on their curves).
#include "anisomesh/mesh/all_quad_split.h"

#include <algorithm>
#include <map>

#include "anisomesh/core/error.h"

namespace anisomesh {

std::vector<EdgeMidpoint> loopEdgeMidpoints(const std::vector<BoundaryLoop>& loops) {
  std::vector<EdgeMidpoint> out;
  int base = 0;
  for (const BoundaryLoop& loop : loops) {
    const int n = static_cast<int>(loop.points.size());
    require(loop.edgeMidpoints.empty() || loop.edgeMidpoints.size() == loop.points.size(), ErrorCode::InvalidArgument,
            "all-quad split: a boundary loop has " + std::to_string(loop.points.size()) + " points but " +
                std::to_string(loop.edgeMidpoints.size()) + " edge midpoints (one per edge expected)");
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const Vec2 m = loop.edgeMidpoints.empty() ? Vec2(0.5 * (loop.points[size_t(i)] + loop.points[size_t(j)]))
                                                : loop.edgeMidpoints[size_t(i)];
      out.push_back({{base + i, base + j}, m});
    }
    base += n;
  }
  return out;
}

std::vector<std::array<int, 2>> splitIntoAllQuads(Mesh& mesh, const std::vector<EdgeMidpoint>& boundary) {
  std::map<std::array<int, 2>, int> mids;
  std::vector<std::array<int, 2>> origin;
  const bool refs = mesh.pointRefs.size() == mesh.points.size();
  auto addPoint = [&](const Vec2& p, std::array<int, 2> from) {
    mesh.points.emplace_back(p.x(), p.y(), 0.0);
    mesh.params.push_back(p);
    if (refs) mesh.pointRefs.push_back(0);
    origin.push_back(from);
    return static_cast<int>(mesh.params.size()) - 1;
  };
  auto key = [](int a, int b) { return std::array<int, 2>{std::min(a, b), std::max(a, b)}; };
  for (const EdgeMidpoint& b : boundary) {
    const auto k = key(b.edge[0], b.edge[1]);
    if (!mids.count(k)) mids[k] = addPoint(b.point, b.edge);
  }
  std::map<std::array<int, 2>, int> boundaryMids = mids;
  auto mid = [&](int a, int b) {
    const auto k = key(a, b);
    const auto it = mids.find(k);
    if (it != mids.end()) return it->second;
    return mids[k] = addPoint(0.5 * (mesh.params[size_t(a)] + mesh.params[size_t(b)]), {-1, -1});
  };
  std::vector<std::array<int, 4>> quads;
  quads.reserve(3 * mesh.triangles.size() + 4 * mesh.quads.size());
  for (const auto& t : mesh.triangles) {
    const int mab = mid(t[0], t[1]), mbc = mid(t[1], t[2]), mca = mid(t[2], t[0]);
    const int g =
        addPoint((mesh.params[size_t(t[0])] + mesh.params[size_t(t[1])] + mesh.params[size_t(t[2])]) / 3.0, {-1, -1});
    quads.push_back({t[0], mab, g, mca});
    quads.push_back({t[1], mbc, g, mab});
    quads.push_back({t[2], mca, g, mbc});
  }
  for (const auto& q : mesh.quads) {
    int m[4];
    for (int k = 0; k < 4; ++k) m[k] = mid(q[size_t(k)], q[size_t((k + 1) % 4)]);
    const int o = addPoint(0.25 * (mesh.params[size_t(q[0])] + mesh.params[size_t(q[1])] + mesh.params[size_t(q[2])] +
                                   mesh.params[size_t(q[3])]),
                           {-1, -1});
    for (int k = 0; k < 4; ++k) quads.push_back({q[size_t(k)], m[k], o, m[(k + 3) % 4]});
  }
  mesh.quads.swap(quads);
  mesh.quadRefs.assign(mesh.quads.size(), 0);
  mesh.triangles.clear();
  mesh.triangleRefs.clear();
  // Boundary edges in two, in their order, keeping their references.
  std::vector<std::array<int, 2>> edges;
  std::vector<int> edgeRefs;
  for (size_t e = 0; e < mesh.edges.size(); ++e) {
    const int a = mesh.edges[e][0], b = mesh.edges[e][1];
    const int r = e < mesh.edgeRefs.size() ? mesh.edgeRefs[e] : 0;
    const auto it = boundaryMids.find(key(a, b));
    if (it == boundaryMids.end()) {
      edges.push_back({a, b});
      edgeRefs.push_back(r);
    } else {
      edges.push_back({a, it->second});
      edges.push_back({it->second, b});
      edgeRefs.push_back(r);
      edgeRefs.push_back(r);
    }
  }
  mesh.edges.swap(edges);
  mesh.edgeRefs.swap(edgeRefs);
  return origin;
}

}  // namespace anisomesh

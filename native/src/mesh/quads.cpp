// Quad conversion: greedy merging of adjacent triangles into the best quads in the metric
// (Blossom-free); the all-quad split that may follow is mesh/all_quad_split.
#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "anisomesh/mesh/predicates.h"
#include "mesh_internal.h"

namespace anisomesh {
namespace {

inline std::uint64_t edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

void mergeTriangles(Mesh& mesh, const std::vector<SymMt>& vmt, double minQuality) {
  const int nt = static_cast<int>(mesh.triangles.size());
  struct HalfEdge {
    std::uint64_t key;
    int tri, local;
  };
  std::vector<HalfEdge> hes;
  hes.reserve(3 * nt);
  for (int t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i)
      hes.push_back({edgeKey(mesh.triangles[t][(i + 1) % 3], mesh.triangles[t][(i + 2) % 3]), t, i});
  std::sort(hes.begin(), hes.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.key, x.tri, x.local) < std::tie(y.key, y.tri, y.local);
  });
  std::vector<std::uint64_t> boundaryKeys;
  for (const auto& e : mesh.edges) boundaryKeys.push_back(edgeKey(e[0], e[1]));
  std::sort(boundaryKeys.begin(), boundaryKeys.end());
  struct Candidate {
    double q;
    int t1, t2;
    std::array<int, 4> quad;
  };
  std::vector<Candidate> cands;
  for (size_t k = 0; k + 1 < hes.size(); ++k) {
    if (hes[k].key != hes[k + 1].key) continue;
    if (std::binary_search(boundaryKeys.begin(), boundaryKeys.end(), hes[k].key)) continue;
    const auto& t1 = mesh.triangles[hes[k].tri];
    const auto& t2 = mesh.triangles[hes[k + 1].tri];
    const int i = hes[k].local;
    const int p = t1[i], u = t1[(i + 1) % 3], w = t1[(i + 2) % 3];
    const int j = hes[k + 1].local;
    const int q = t2[j];
    const std::array<int, 4> quad{p, u, q, w};
    Vec2 pts[4];
    for (int c = 0; c < 4; ++c) pts[c] = mesh.params[quad[c]];
    bool convex = true;
    for (int c = 0; c < 4 && convex; ++c) convex = orient2d(pts[(c + 3) % 4], pts[c], pts[(c + 1) % 4]) > 0.0;
    if (!convex) continue;
    const SymMt m{0.25 * (vmt[p].a + vmt[u].a + vmt[q].a + vmt[w].a),
                  0.25 * (vmt[p].b + vmt[u].b + vmt[q].b + vmt[w].b),
                  0.25 * (vmt[p].c + vmt[u].c + vmt[q].c + vmt[w].c)};
    const double quality = metricQuadQuality(m, pts);
    if (quality < minQuality) continue;
    cands.push_back({quality, hes[k].tri, hes[k + 1].tri, quad});
  }
  std::sort(cands.begin(), cands.end(), [](const Candidate& x, const Candidate& y) {
    return x.q > y.q || (x.q == y.q && std::tie(x.t1, x.t2) < std::tie(y.t1, y.t2));
  });
  std::vector<char> used(nt, 0);
  for (const auto& c : cands) {
    if (used[c.t1] || used[c.t2]) continue;
    used[c.t1] = used[c.t2] = 1;
    mesh.quads.push_back(c.quad);
  }
  std::vector<std::array<int, 3>> rest;
  for (int t = 0; t < nt; ++t)
    if (!used[t]) rest.push_back(mesh.triangles[t]);
  mesh.triangles.swap(rest);
  mesh.triangleRefs.assign(mesh.triangles.size(), 0);
  mesh.quadRefs.assign(mesh.quads.size(), 0);
}

}  // namespace

void convertToQuads(Mesh& mesh, const std::vector<SymMt>& vertexMt, double minQuadQuality) {
  mergeTriangles(mesh, vertexMt, minQuadQuality);
}

}  // namespace anisomesh

// Surface meshing: merging of the patch meshes (orientation across shared curves, all-quad
// split of a patch mesh, open edges).
#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

// Flips whole patches so that elements on both sides of every shared edge traverse it in
// opposite directions (one consistent 3D orientation), starting from the first patch of
// each connected group; a patch whose sharing contradicts itself (non-orientable) is left.
// patchTriangles / patchQuads: element counts per patch, in the order of out's lists.
void orientPatches(Mesh& out, const std::vector<int>& patchTriangles, const std::vector<int>& patchQuads,
                   const std::set<std::array<int, 2>>& shared) {
  const size_t np = patchTriangles.size();
  std::vector<int> triPatch, quadPatch;
  for (size_t p = 0; p < np; ++p) {
    triPatch.insert(triPatch.end(), size_t(patchTriangles[p]), int(p));
    quadPatch.insert(quadPatch.end(), size_t(patchQuads[p]), int(p));
  }
  // For each shared edge, the (patch, +1/-1 direction) of its elements.
  std::map<std::array<int, 2>, std::vector<std::pair<int, int>>> uses;
  auto visit = [&](const int* v, int n, int patch) {
    for (int k = 0; k < n; ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      const std::array<int, 2> e{std::min(a, b), std::max(a, b)};
      if (shared.count(e)) uses[e].push_back({patch, a < b ? 1 : -1});
    }
  };
  for (size_t t = 0; t < out.triangles.size(); ++t) visit(out.triangles[t].data(), 3, triPatch[t]);
  for (size_t t = 0; t < out.quads.size(); ++t) visit(out.quads[t].data(), 4, quadPatch[t]);
  // Graph: patches p, q must flip alike (0) or oppositely (1).
  std::vector<std::vector<std::pair<int, int>>> adj(np);
  for (const auto& u : uses)
    if (u.second.size() == 2 && u.second[0].first != u.second[1].first) {
      const int differ = u.second[0].second == u.second[1].second ? 1 : 0;
      adj[size_t(u.second[0].first)].push_back({u.second[1].first, differ});
      adj[size_t(u.second[1].first)].push_back({u.second[0].first, differ});
    }
  std::vector<int> flip(np, -1);
  for (size_t s = 0; s < np; ++s) {
    if (flip[s] >= 0) continue;
    flip[s] = 0;
    std::vector<int> stack{int(s)};
    while (!stack.empty()) {
      const int p = stack.back();
      stack.pop_back();
      for (const auto& e : adj[size_t(p)])
        if (flip[size_t(e.first)] < 0) {
          flip[size_t(e.first)] = flip[size_t(p)] ^ e.second;
          stack.push_back(e.first);
        }
    }
  }
  for (size_t t = 0; t < out.triangles.size(); ++t)
    if (flip[size_t(triPatch[t])] == 1) std::swap(out.triangles[t][1], out.triangles[t][2]);
  for (size_t t = 0; t < out.quads.size(); ++t)
    if (flip[size_t(quadPatch[t])] == 1) std::swap(out.quads[t][1], out.quads[t][3]);
}

}  // namespace surface_mesher

std::vector<std::array<int, 2>> openEdges(const Mesh& mesh) {
  std::map<std::array<int, 2>, int> count;
  auto visit = [&](const int* v, int n) {
    for (int k = 0; k < n; ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  };
  for (const auto& t : mesh.triangles) visit(t.data(), 3);
  for (const auto& q : mesh.quads) visit(q.data(), 4);
  std::vector<std::array<int, 2>> out;
  for (const auto& e : count)
    if (e.second == 1) out.push_back(e.first);
  return out;
}

}  // namespace anisomesh

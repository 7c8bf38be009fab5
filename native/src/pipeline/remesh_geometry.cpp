#include "anisomesh/pipeline/remesh_geometry.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {
namespace {

// Boundary edges of the elements: the element edges used once, in the order of their
// (smaller, larger) vertex pair. Linear time and 4 bytes per element edge: the edges are
// bucketed by their smaller vertex (counting sort), each bucket (a few entries) sorted.
template <class F>
void forEachBoundaryEdge(const Mesh& mesh, F&& emit) {
  const size_t nv = mesh.points.size();
  const size_t halfEdges = 3 * mesh.triangles.size() + 4 * mesh.quads.size();
  require(std::uint64_t(halfEdges) < (std::uint64_t(1) << 32) && std::uint64_t(nv) < (std::uint64_t(1) << 31),
          ErrorCode::InvalidArgument, "the mesh is too large to extract its boundary");
  auto forEachElementEdge = [&](auto&& f) {
    auto visit = [&](const int* v, int n) {
      for (int k = 0; k < n; ++k) f(v[k], v[(k + 1) % n]);
    };
    for (const auto& t : mesh.triangles) visit(t.data(), 3);
    for (const auto& q : mesh.quads) visit(q.data(), 4);
  };
  std::vector<std::uint32_t> start(nv + 1, 0);
  forEachElementEdge([&](int a, int b) {
    if (a < 0 || b < 0 || size_t(a) >= nv || size_t(b) >= nv)
      throw Error(ErrorCode::InvalidArgument, "an element refers to vertex " +
                                                  std::to_string((a < 0 || size_t(a) >= nv ? a : b) + 1) + " of " +
                                                  std::to_string(nv));
    ++start[size_t(std::min(a, b)) + 1];
  });
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  // Entry: larger vertex << 1 | 1 when the element runs from the larger to the smaller.
  std::vector<std::uint32_t> other(halfEdges);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  forEachElementEdge([&](int a, int b) {
    const int lo = std::min(a, b), hi = std::max(a, b);
    other[fill[size_t(lo)]++] = (std::uint32_t(hi) << 1) | (a == hi ? 1u : 0u);
  });
  std::vector<std::uint32_t>().swap(fill);
  for (size_t v = 0; v < nv; ++v) {
    std::uint32_t* b = other.data() + start[v];
    std::uint32_t* e = other.data() + start[v + 1];
    std::sort(b, e);
    for (std::uint32_t* i = b; i < e;) {
      std::uint32_t* j = i + 1;
      while (j < e && (*j >> 1) == (*i >> 1)) ++j;
      if (j - i == 1) {
        const int hi = int(*i >> 1);
        if (*i & 1u)
          emit(hi, int(v));
        else
          emit(int(v), hi);
      }
      i = j;
    }
  }
}

}  // namespace

std::vector<BoundaryLoop> boundaryLoopsFromMesh(const Mesh& mesh) {
  for (size_t i = 0; i < mesh.points.size(); ++i)
    if (mesh.points[i].z() != 0.0)  // (the message is built only on failure: 1M+ vertices)
      throw Error(ErrorCode::InvalidDomain, "remeshing needs a planar mesh (z = 0), vertex " + std::to_string(i + 1) +
                                                " has z = " + std::to_string(mesh.points[i].z()));
  // The Edges section's references by (smaller, larger) vertex; of repeated edges the last.
  std::vector<std::pair<std::uint64_t, int>> edgeRef;  // key, index into mesh.edges
  edgeRef.reserve(mesh.edges.size());
  auto key = [](int a, int b) {
    return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
  };
  for (size_t i = 0; i < mesh.edges.size(); ++i) edgeRef.push_back({key(mesh.edges[i][0], mesh.edges[i][1]), int(i)});
  std::sort(edgeRef.begin(), edgeRef.end());
  auto refOf = [&](int a, int b) {
    const std::uint64_t k = key(a, b);
    auto it = std::upper_bound(edgeRef.begin(), edgeRef.end(), std::make_pair(k, INT_MAX));
    if (it == edgeRef.begin() || (it - 1)->first != k) return 0;
    const size_t i = size_t((it - 1)->second);
    return i < mesh.edgeRefs.size() ? mesh.edgeRefs[i] : 0;
  };

  // Directed boundary edges (a, b, ref).
  struct Directed {
    int a, b, ref;
  };
  std::vector<Directed> bnd;
  if (!mesh.triangles.empty() || !mesh.quads.empty()) {
    forEachBoundaryEdge(mesh, [&](int a, int b) { bnd.push_back({a, b, refOf(a, b)}); });
  } else {
    for (size_t i = 0; i < mesh.edges.size(); ++i)
      bnd.push_back({mesh.edges[i][0], mesh.edges[i][1], i < mesh.edgeRefs.size() ? mesh.edgeRefs[i] : 0});
  }
  require(!bnd.empty(), ErrorCode::OpenContour, "the mesh has no boundary edges");

  // Undirected chaining: every boundary vertex must have exactly two boundary edges
  // (the first two incident edges kept per vertex, in the order of bnd).
  const size_t nv = mesh.points.size();
  std::vector<int> degree(nv, 0), inc0(nv, -1), inc1(nv, -1);
  for (int i = 0; i < int(bnd.size()); ++i)
    for (const int v : {bnd[size_t(i)].a, bnd[size_t(i)].b}) {
      if (v < 0 || size_t(v) >= nv)
        throw Error(ErrorCode::InvalidArgument,
                    "an edge refers to vertex " + std::to_string(v + 1) + " of " + std::to_string(nv));
      int& d = degree[size_t(v)];
      (d == 0 ? inc0 : inc1)[size_t(v)] = d < 2 ? i : inc1[size_t(v)];
      ++d;
    }
  for (size_t v = 0; v < nv; ++v) {
    if (degree[v] == 0 || degree[v] == 2) continue;
    const Vec3& p = mesh.points[v];
    require(false, ErrorCode::OpenContour,
            "boundary vertex " + std::to_string(v + 1) + " " + formatPoint(p.head<2>()) + " has " +
                std::to_string(degree[v]) +
                " boundary edges (2 expected): the boundary edges do not form closed loops");
  }
  std::vector<bool> used(bnd.size(), false);
  std::vector<BoundaryLoop> loops;
  for (int s = 0; s < int(bnd.size()); ++s) {
    if (used[size_t(s)]) continue;
    BoundaryLoop loop;
    int e = s, from = bnd[size_t(s)].a;
    while (!used[size_t(e)]) {
      used[size_t(e)] = true;
      const int to = bnd[size_t(e)].a == from ? bnd[size_t(e)].b : bnd[size_t(e)].a;
      loop.points.push_back(mesh.points[size_t(from)].head<2>());
      loop.edgeRefs.push_back(bnd[size_t(e)].ref);
      e = inc0[size_t(to)] == e ? inc1[size_t(to)] : inc0[size_t(to)];
      from = to;
    }
    require(loop.points.size() >= 3, ErrorCode::OpenContour, "a boundary loop has fewer than 3 edges");
    loops.push_back(std::move(loop));
  }

  // Outer loop first; orientation outer counter-clockwise, holes clockwise.
  std::vector<double> area;
  area.reserve(loops.size());
  for (const auto& l : loops) area.push_back(signedArea(l.points));
  size_t outer = 0;
  for (size_t i = 1; i < loops.size(); ++i)
    if (std::abs(area[i]) > std::abs(area[outer])) outer = i;
  std::swap(loops[0], loops[outer]);
  std::swap(area[0], area[outer]);
  for (size_t i = 0; i < loops.size(); ++i) {
    if ((area[i] > 0) != (i == 0)) {
      BoundaryLoop& l = loops[i];
      const int n = int(l.points.size());
      BoundaryLoop rev;
      for (int k = 0; k < n; ++k) {
        rev.points.push_back(l.points[size_t(n - 1 - k)]);
        rev.edgeRefs.push_back(l.edgeRefs[size_t(((n - 2 - k) % n + n) % n)]);
      }
      l = std::move(rev);
    }
  }
  for (size_t i = 1; i < loops.size(); ++i) {
    require(pointInPolygon(loops[0].points, loops[i].points[0]), ErrorCode::InvalidDomain,
            "boundary loop at " + formatPoint(loops[i].points[0]) +
                " is outside the outer loop: several components are not supported");
    for (size_t j = 1; j < loops.size(); ++j)
      require(j == i || !pointInPolygon(loops[j].points, loops[i].points[0]), ErrorCode::InvalidDomain,
              "boundary loop at " + formatPoint(loops[i].points[0]) + " lies inside a hole: islands are not supported");
  }
  return loops;
}

Domain domainFromBoundaryLoops(const std::vector<BoundaryLoop>& loops, const LoopDomainOptions& options) {
  Domain domain;
  for (size_t li = 0; li < loops.size(); ++li) {
    const BoundaryLoop& l = loops[li];
    const int n = int(l.points.size());
    // Vertex k is a break when the ref changes there or the boundary turns sharply.
    auto isBreak = [&](int k) {
      const int prev = (k + n - 1) % n;
      if (l.edgeRefs[size_t(prev)] != l.edgeRefs[size_t(k)]) return true;
      const Vec2 u = l.points[size_t(k)] - l.points[size_t(prev)],
                 v = l.points[size_t((k + 1) % n)] - l.points[size_t(k)];
      const double turn = pm::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
      return std::abs(turn) > options.cornerAngle;
    };
    std::vector<int> breaks;
    for (int k = 0; k < n; ++k)
      if (isBreak(k)) breaks.push_back(k);
    Contour contour;
    const bool cornerFree = breaks.empty();
    if (cornerFree) {
      // A smooth closed loop: split it in three pieces so each stays a simple curve.
      breaks = {0, n / 3, (2 * n) / 3};
    }
    for (size_t b = 0; b < breaks.size(); ++b) {
      const int from = breaks[b], to = breaks[(b + 1) % breaks.size()];
      std::vector<Vec2> pts;
      int k = from;
      do {
        pts.push_back(l.points[size_t(k)]);
        k = (k + 1) % n;
      } while (k != to);
      pts.push_back(l.points[size_t(to)]);
      if (!options.smooth) {
        contour.add(std::make_shared<PolylineCurve>(std::move(pts), l.edgeRefs[size_t(from)], false));
        continue;
      }
      // Splits of a corner-free loop join C1: the tangents there see across them.
      const Vec2 before = l.points[size_t((from + n - 1) % n)], after = l.points[size_t((to + 1) % n)];
      contour.add(std::make_shared<SplineCurve>(std::move(pts), l.edgeRefs[size_t(from)],
                                                cornerFree ? &before : nullptr, cornerFree ? &after : nullptr));
    }
    if (li == 0)
      domain.outer = std::move(contour);
    else
      domain.holes.push_back(std::move(contour));
  }
  return domain;
}

std::vector<Metric> clampMetricSizes(const std::vector<Metric>& metrics, double hmin, double hmax) {
  std::vector<Metric> out;
  out.reserve(metrics.size());
  for (const Metric& m : metrics) {
    const MetricSizes s = m.sizes();
    double h1 = s.h1, h2 = s.h2;
    if (hmin > 0) h1 = std::max(h1, hmin), h2 = std::max(h2, hmin);
    if (hmax > 0) h1 = std::min(h1, hmax), h2 = std::min(h2, hmax);
    out.push_back(h1 == s.h1 && h2 == s.h2 ? m : Metric::fromSizes(s.alpha, h1, h2));
  }
  return out;
}

}  // namespace anisomesh

#include "anisomesh/pipeline/remesh_geometry.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {
namespace {

// Calls f(a, b) for every edge of the elements [begin, end): triangles, then quadrilaterals.
template <class F>
void forEachElementEdge(const Mesh& mesh, size_t begin, size_t end, F&& f) {
  const size_t nt = mesh.triangles.size();
  for (size_t i = begin; i < std::min(end, nt); ++i) {
    const auto& t = mesh.triangles[i];
    f(t[0], t[1]), f(t[1], t[2]), f(t[2], t[0]);
  }
  for (size_t i = std::max(begin, nt); i < end; ++i) {
    const auto& q = mesh.quads[i - nt];
    f(q[0], q[1]), f(q[1], q[2]), f(q[2], q[3]), f(q[3], q[0]);
  }
}

// Element ranges of the boundary extraction at most (each has a count per vertex).
constexpr size_t kMaxRanges = 4;
// Vertices per parallel chunk of the buckets' offsets and sorting.
constexpr size_t kVertexChunk = 65536;

// Boundary edges of the elements: the element edges used once, in the order of their
// (smaller, larger) vertex pair, directed as their element runs. Linear time and 4 bytes
// per element edge: the edges are bucketed by their smaller vertex (a counting sort),
// each bucket (a few entries) sorted. In parallel: each thread counts and places the
// edges of a range of elements (a count per vertex and range), the buckets are sorted
// and scanned in chunks of vertices; sorted buckets do not depend on the ranges.
std::vector<std::array<int, 2>> boundaryEdges(const Mesh& mesh) {
  const size_t nv = mesh.points.size();
  const size_t elements = mesh.triangles.size() + mesh.quads.size();
  const size_t halfEdges = 3 * mesh.triangles.size() + 4 * mesh.quads.size();
  require(std::uint64_t(halfEdges) < (std::uint64_t(1) << 32) && std::uint64_t(nv) < (std::uint64_t(1) << 31),
          ErrorCode::InvalidArgument, "the mesh is too large to extract its boundary");
  const size_t ranges = std::max<size_t>(1, std::min({size_t(threadCount()), kMaxRanges, elements}));
  auto rangeBegin = [&](size_t r) { return elements * r / ranges; };
  // count[r][v]: the edges of range r whose smaller vertex is v; then where range r's
  // first such edge goes, advanced as they are placed (the last range's: to the end of
  // v's bucket). The lowest range's error (the first vertex out of range) is rethrown.
  // (One block, allocated here: the main heap reuses what the reading freed; a worker's
  // own heap would map fresh memory, whose first touch is costly on a virtual machine.)
  const std::unique_ptr<std::uint32_t[]> counts(new std::uint32_t[ranges * nv]);
  auto count = [&](size_t r) { return counts.get() + r * nv; };
  parallelChunks(ranges, 1, [&](size_t r, size_t, size_t) {
    std::uint32_t* const c = count(r);
    std::fill(c, c + nv, 0u);
    forEachElementEdge(mesh, rangeBegin(r), rangeBegin(r + 1), [&](int a, int b) {
      if (std::uint32_t(a) >= nv || std::uint32_t(b) >= nv)
        throw Error(ErrorCode::InvalidArgument, "an element refers to vertex " +
                                                    std::to_string((std::uint32_t(a) >= nv ? a : b) + 1) + " of " +
                                                    std::to_string(nv));
      ++c[std::min(a, b)];
    });
  });
  // The offsets: per chunk of vertices its edges, then each chunk's from its start.
  const size_t chunks = chunkCount(nv, kVertexChunk);
  std::vector<std::uint32_t> chunkStart(chunks + 1, 0);
  parallelChunks(nv, kVertexChunk, [&](size_t chunk, size_t b, size_t e) {
    std::uint32_t sum = 0;
    for (size_t r = 0; r < ranges; ++r)
      for (size_t v = b; v < e; ++v) sum += count(r)[v];
    chunkStart[chunk + 1] = sum;
  });
  for (size_t c = 0; c < chunks; ++c) chunkStart[c + 1] += chunkStart[c];
  parallelChunks(nv, kVertexChunk, [&](size_t chunk, size_t b, size_t e) {
    std::uint32_t at = chunkStart[chunk];
    for (size_t v = b; v < e; ++v)
      for (size_t r = 0; r < ranges; ++r) {
        const std::uint32_t n = count(r)[v];
        count(r)[v] = at;
        at += n;
      }
  });
  // Entry: larger vertex << 1 | 1 when the element runs from the larger to the smaller.
  // (Not zero-filled: the placing touches it first, in parallel.)
  const std::unique_ptr<std::uint32_t[]> other(new std::uint32_t[halfEdges]);
  parallelChunks(ranges, 1, [&](size_t r, size_t, size_t) {
    std::uint32_t* const c = count(r);
    forEachElementEdge(mesh, rangeBegin(r), rangeBegin(r + 1), [&](int a, int b) {
      const int lo = std::min(a, b), hi = std::max(a, b);
      other[c[lo]++] = (std::uint32_t(hi) << 1) | (a == hi ? 1u : 0u);
    });
  });
  // Bucket v ends where the last range's entries of v end: count[ranges - 1][v].
  const std::uint32_t* const bucketEnd = count(ranges - 1);
  std::vector<std::vector<std::array<int, 2>>> found(chunks);
  parallelChunks(nv, kVertexChunk, [&](size_t chunk, size_t vb, size_t ve) {
    for (size_t v = vb; v < ve; ++v) {
      std::uint32_t* const b = other.get() + (v == 0 ? 0 : bucketEnd[v - 1]);
      std::uint32_t* const e = other.get() + bucketEnd[v];
      for (std::uint32_t* k = b + 1; k < e; ++k) {  // insertion sort (about six entries per vertex)
        const std::uint32_t x = *k;
        std::uint32_t* m = k;
        for (; m > b && m[-1] > x; --m) *m = m[-1];
        *m = x;
      }
      for (std::uint32_t* i = b; i < e;) {
        std::uint32_t* j = i + 1;
        while (j < e && (*j >> 1) == (*i >> 1)) ++j;
        if (j - i == 1) {
          const int hi = int(*i >> 1);
          found[chunk].push_back(*i & 1u ? std::array<int, 2>{hi, int(v)} : std::array<int, 2>{int(v), hi});
        }
        i = j;
      }
    }
  });
  std::vector<std::array<int, 2>> edges;
  for (const auto& f : found) edges.insert(edges.end(), f.begin(), f.end());
  return edges;
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
    for (const auto& [a, b] : boundaryEdges(mesh)) bnd.push_back({a, b, refOf(a, b)});
  } else {
    for (size_t i = 0; i < mesh.edges.size(); ++i)
      bnd.push_back({mesh.edges[i][0], mesh.edges[i][1], i < mesh.edgeRefs.size() ? mesh.edgeRefs[i] : 0});
  }
  require(!bnd.empty(), ErrorCode::OpenContour, "the mesh has no boundary edges");

  // Undirected chaining: every boundary vertex must have exactly two boundary edges
  // (the first two incident edges kept per vertex, in the order of bnd). The edges' ends
  // as (vertex, edge) pairs, sorted: a vertex's incident edges are adjacent, in bnd order.
  const size_t nv = mesh.points.size();
  std::vector<std::uint64_t> ends;
  ends.reserve(2 * bnd.size());
  for (int i = 0; i < int(bnd.size()); ++i)
    for (const int v : {bnd[size_t(i)].a, bnd[size_t(i)].b}) {
      if (v < 0 || size_t(v) >= nv)
        throw Error(ErrorCode::InvalidArgument,
                    "an edge refers to vertex " + std::to_string(v + 1) + " of " + std::to_string(nv));
      ends.push_back(std::uint64_t(v) << 32 | std::uint32_t(i));
    }
  std::sort(ends.begin(), ends.end());
  for (size_t k = 0; k < ends.size();) {
    size_t j = k + 1;
    while (j < ends.size() && ends[j] >> 32 == ends[k] >> 32) ++j;
    const size_t v = size_t(ends[k] >> 32);
    if (j - k != 2)  // (the message is built only on failure)
      throw Error(ErrorCode::OpenContour,
                  "boundary vertex " + std::to_string(v + 1) + " " + formatPoint(mesh.points[v].head<2>()) + " has " +
                      std::to_string(j - k) +
                      " boundary edges (2 expected): the boundary edges do not form closed loops");
    k = j;
  }
  // The boundary edge at vertex v other than e.
  auto nextAt = [&](int v, int e) {
    const auto at = std::lower_bound(ends.begin(), ends.end(), std::uint64_t(v) << 32);
    const int e0 = int(at[0] & 0xffffffffu), e1 = int(at[1] & 0xffffffffu);
    return e0 == e ? e1 : e0;
  };
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
      e = nextAt(to, e);
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

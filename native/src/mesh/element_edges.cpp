#include "anisomesh/mesh/element_edges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "anisomesh/core/parallel.h"

namespace anisomesh {
namespace {

constexpr size_t kChunk = 65536;  // vertices or elements per parallel chunk

// Calls f(a, b, element) for every element edge, elements in order.
template <class F>
void forEachEdge(const Mesh& mesh, F&& f) {
  const int nt = int(mesh.triangles.size());
  for (int i = 0; i < nt; ++i) {
    const auto& t = mesh.triangles[size_t(i)];
    f(t[0], t[1], i), f(t[1], t[2], i), f(t[2], t[0], i);
  }
  for (size_t i = 0; i < mesh.quads.size(); ++i) {
    const auto& q = mesh.quads[i];
    const int e = nt + int(i);
    f(q[0], q[1], e), f(q[1], q[2], e), f(q[2], q[3], e), f(q[3], q[0], e);
  }
}

}  // namespace

ElementEdges elementEdges(const Mesh& mesh) {
  ElementEdges out;
  int lo = 0, hi = -1;
  forEachEdge(mesh, [&](int a, int b, int) {
    lo = std::min({lo, a, b});
    hi = std::max({hi, a, b});
  });
  if (lo < 0) {  // not a valid mesh: packed (a, b) keys, which sort as the pairs do; no owners
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * mesh.triangles.size() + 4 * mesh.quads.size());
    forEachEdge(mesh, [&](int a, int b, int) {
      if (a > b) std::swap(a, b);
      keys.push_back((std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b));
    });
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    out.edges.resize(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) out.edges[i] = {int(keys[i] >> 32), int(keys[i] & 0xffffffffu)};
    return out;
  }
  // (larger end, element) entries bucketed by the smaller end (a counting sort, elements
  // in order), each bucket's few entries sorted on the larger end (stable: owners stay in
  // element order), then the distinct ends counted and written per chunk of vertices at
  // each chunk's offsets: the same lists for any thread count.
  struct Entry {
    int other;
    int element;
  };
  const size_t n = size_t(hi) + 1;
  std::vector<int> start(n + 1, 0);
  forEachEdge(mesh, [&](int a, int b, int) { ++start[size_t(std::min(a, b)) + 1]; });
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<Entry> entries(static_cast<size_t>(start[n]));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    forEachEdge(mesh, [&](int a, int b, int e) {
      entries[size_t(fill[size_t(std::min(a, b))]++)] = {std::max(a, b), e};
    });
  }
  std::vector<size_t> edgeOffset(chunkCount(n, kChunk) + 1, 0);
  parallelChunks(n, kChunk, [&](size_t chunk, size_t vb, size_t ve) {
    size_t distinct = 0;
    for (size_t v = vb; v < ve; ++v) {
      Entry* const b = entries.data() + start[v];
      Entry* const e = entries.data() + start[v + 1];
      for (Entry* k = b + 1; k < e; ++k) {  // insertion sort (about six entries per vertex)
        const Entry x = *k;
        Entry* m = k;
        for (; m > b && m[-1].other > x.other; --m) *m = m[-1];
        *m = x;
      }
      for (Entry* k = b; k < e; ++k) distinct += (k == b || k->other != k[-1].other) ? 1 : 0;
    }
    edgeOffset[chunk + 1] = distinct;
  });
  for (size_t c = 1; c < edgeOffset.size(); ++c) edgeOffset[c] += edgeOffset[c - 1];
  out.edges.resize(edgeOffset.back());
  out.ownerStart.resize(out.edges.size() + 1);
  out.owners.resize(entries.size());
  parallelChunks(n, kChunk, [&](size_t chunk, size_t vb, size_t ve) {
    size_t k = edgeOffset[chunk];
    for (size_t v = vb; v < ve; ++v) {
      const Entry* const b = entries.data() + start[v];
      const Entry* const e = entries.data() + start[v + 1];
      for (const Entry* i = b; i < e; ++i) {
        // (the owners keep the entries' places: a chunk's owners start at start[vb])
        const size_t at = size_t(i - entries.data());
        if (i == b || i->other != i[-1].other) out.edges[k] = {int(v), i->other}, out.ownerStart[k++] = int(at);
        out.owners[at] = i->element;
      }
    }
  });
  out.ownerStart.back() = int(entries.size());
  return out;
}

double largestNeighbourSizeRatio(const Mesh& mesh, const ElementEdges& edges) {
  if (edges.owners.empty()) return 1.0;
  const bool useParams = mesh.params.size() == mesh.points.size();
  auto xy = [&](int i) { return useParams ? mesh.params[size_t(i)] : Vec2(mesh.points[size_t(i)].head<2>()); };
  auto area = [&](int a, int b, int c) {
    const Vec2 pa = xy(a), pb = xy(b), pc = xy(c);
    return 0.5 * ((pb.x() - pa.x()) * (pc.y() - pa.y()) - (pb.y() - pa.y()) * (pc.x() - pa.x()));
  };
  const size_t nt = mesh.triangles.size();
  std::vector<double> size(nt + mesh.quads.size());
  parallelChunks(size.size(), kChunk, [&](size_t, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (i < nt) {
        const auto& t = mesh.triangles[i];
        size[i] = std::sqrt(std::abs(area(t[0], t[1], t[2])));
      } else {
        const auto& q = mesh.quads[i - nt];
        size[i] = std::sqrt(std::abs(area(q[0], q[1], q[2]) + area(q[0], q[2], q[3])));
      }
    }
  });
  // Per chunk of edges, then the largest over chunks (a max: the same for any order).
  std::vector<double> worstOf(chunkCount(edges.edges.size(), kChunk), 1.0);
  parallelChunks(edges.edges.size(), kChunk, [&](size_t chunk, size_t b, size_t e) {
    double worst = 1.0;
    for (size_t k = b; k < e; ++k) {
      const int first = edges.ownerStart[k], last = edges.ownerStart[k + 1];
      const double a = size[size_t(edges.owners[size_t(first)])];
      for (int j = first + 1; j < last; ++j) {
        const double c = size[size_t(edges.owners[size_t(j)])];
        if (a > 0 && c > 0) worst = std::max(worst, std::max(a, c) / std::min(a, c));
      }
    }
    worstOf[chunk] = worst;
  });
  return worstOf.empty() ? 1.0 : *std::max_element(worstOf.begin(), worstOf.end());
}

}  // namespace anisomesh

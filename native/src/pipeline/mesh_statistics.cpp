#include "anisomesh/pipeline/mesh_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "anisomesh/core/parallel.h"
#include "anisomesh/mesh/quality.h"

namespace anisomesh {
namespace {

constexpr size_t kChunk = 65536;  // elements or vertices per parallel chunk

Vec2 xy(const Mesh& m, int i) { return m.params.size() == m.points.size() ? m.params[i] : Vec2(m.points[i].head<2>()); }

double signedArea(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}

double triangleQuality(const Vec2& a, const Vec2& b, const Vec2& c, const Mat2& mt) {
  const double area = signedArea(a, b, c);
  if (!(area > 0)) return 0.0;
  const double areaM = area * std::abs(mt.determinant());
  const double l2 = (mt * (b - a)).squaredNorm() + (mt * (c - b)).squaredNorm() + (mt * (a - c)).squaredNorm();
  return l2 > 0 ? std::min(1.0, 4.0 * std::sqrt(3.0) * areaM / l2) : 0.0;
}

}  // namespace

double largestNeighbourSizeRatio(const Mesh& mesh) {
  const size_t nt = mesh.triangles.size();
  std::vector<double> size(nt + mesh.quads.size());
  parallelChunks(size.size(), kChunk, [&](size_t, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (i < nt) {
        const auto& t = mesh.triangles[i];
        size[i] = std::sqrt(std::abs(signedArea(xy(mesh, t[0]), xy(mesh, t[1]), xy(mesh, t[2]))));
      } else {
        const auto& q = mesh.quads[i - nt];
        size[i] = std::sqrt(std::abs(signedArea(xy(mesh, q[0]), xy(mesh, q[1]), xy(mesh, q[2])) +
                                     signedArea(xy(mesh, q[0]), xy(mesh, q[2]), xy(mesh, q[3]))));
      }
    }
  });
  // (edge, element) pairs by edge then element: each later owner of an edge is compared
  // with its first (lowest-numbered) owner. Bucketed by the edge's smaller vertex (a
  // counting sort), each bucket sorted by the larger one (stable: elements stay in order).
  auto forEachEdge = [&](auto&& f) {
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) f(mesh.triangles[i][k], mesh.triangles[i][(k + 1) % 3], int(i));
    for (size_t i = 0; i < mesh.quads.size(); ++i)
      for (int k = 0; k < 4; ++k) f(mesh.quads[i][k], mesh.quads[i][(k + 1) % 4], int(mesh.triangles.size() + i));
  };
  int lo = 0, hi = -1;
  forEachEdge([&](int a, int b, int) {
    lo = std::min({lo, a, b});
    hi = std::max({hi, a, b});
  });
  if (lo < 0) return 1.0;  // not a valid mesh (negative vertex index): nothing to compare
  struct Owner {
    int other;
    int element;
  };
  const size_t n = size_t(hi) + 1;
  std::vector<int> start(n + 1, 0);
  forEachEdge([&](int a, int b, int) { ++start[size_t(std::min(a, b)) + 1]; });
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<Owner> owners(static_cast<size_t>(start[n]));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    forEachEdge([&](int a, int b, int e) { owners[size_t(fill[size_t(std::min(a, b))]++)] = {std::max(a, b), e}; });
  }
  // Per chunk of smaller vertices (each owns its buckets), then the largest over chunks.
  std::vector<double> worstOf(chunkCount(n, kChunk), 1.0);
  parallelChunks(n, kChunk, [&](size_t chunk, size_t vb, size_t ve) {
    double worst = 1.0;
    for (size_t v = vb; v < ve; ++v) {
      Owner* const b = owners.data() + start[v];
      Owner* const e = owners.data() + start[v + 1];
      for (Owner* k = b + 1; k < e; ++k) {  // stable insertion sort on the larger vertex
        const Owner x = *k;
        Owner* m = k;
        for (; m > b && m[-1].other > x.other; --m) *m = m[-1];
        *m = x;
      }
      for (Owner* i = b; i < e;) {
        Owner* j = i + 1;
        const double a = size[size_t(i->element)];
        for (; j < e && j->other == i->other; ++j) {
          const double c = size[size_t(j->element)];
          if (a > 0 && c > 0) worst = std::max(worst, std::max(a, c) / std::min(a, c));
        }
        i = j;
      }
    }
    worstOf[chunk] = worst;
  });
  return worstOf.empty() ? 1.0 : *std::max_element(worstOf.begin(), worstOf.end());
}

std::vector<double> elementQualities(const Mesh& mesh, const ControlSpace& cs) {
  std::vector<Mat2> mt(mesh.points.size());
  for (int i = 0; i < mesh.vertexCount(); ++i) mt[size_t(i)] = cs.metricAt(xy(mesh, i)).transform();
  std::vector<double> out;
  out.reserve(size_t(mesh.elementCount()));
  for (const auto& t : mesh.triangles)
    out.push_back(
        triangleQuality(xy(mesh, t[0]), xy(mesh, t[1]), xy(mesh, t[2]), (mt[t[0]] + mt[t[1]] + mt[t[2]]) / 3.0));
  for (const auto& q : mesh.quads) {
    const Mat2 m = (mt[q[0]] + mt[q[1]] + mt[q[2]] + mt[q[3]]) / 4.0;
    const Vec2 p[4] = {xy(mesh, q[0]), xy(mesh, q[1]), xy(mesh, q[2]), xy(mesh, q[3])};
    const bool d02 = (p[2] - p[0]).norm() <= (p[3] - p[1]).norm();
    out.push_back(d02 ? std::min(triangleQuality(p[0], p[1], p[2], m), triangleQuality(p[0], p[2], p[3], m))
                      : std::min(triangleQuality(p[0], p[1], p[3], m), triangleQuality(p[1], p[2], p[3], m)));
  }
  return out;
}

}  // namespace anisomesh

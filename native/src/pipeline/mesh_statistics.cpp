#include "anisomesh/pipeline/mesh_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "anisomesh/mesh/quality.h"

namespace anisomesh {
namespace {

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
  std::vector<double> size;
  size.reserve(mesh.triangles.size() + mesh.quads.size());
  for (const auto& t : mesh.triangles)
    size.push_back(std::sqrt(std::abs(signedArea(xy(mesh, t[0]), xy(mesh, t[1]), xy(mesh, t[2])))));
  for (const auto& q : mesh.quads)
    size.push_back(std::sqrt(std::abs(signedArea(xy(mesh, q[0]), xy(mesh, q[1]), xy(mesh, q[2])) +
                                      signedArea(xy(mesh, q[0]), xy(mesh, q[2]), xy(mesh, q[3])))));
  // (edge, element) pairs sorted by edge then element: each later owner of an edge is
  // compared with its first (lowest-numbered) owner. A sorted array instead of a map:
  // several times faster for 100k+ edges.
  struct Owner {
    std::uint64_t edge;
    std::uint32_t element;
  };
  std::vector<Owner> owners;
  owners.reserve(3 * mesh.triangles.size() + 4 * mesh.quads.size());
  auto visit = [&](int element, const int* v, int n) {
    for (int k = 0; k < n; ++k) {
      const auto a = static_cast<std::uint32_t>(std::min(v[k], v[(k + 1) % n]));
      const auto b = static_cast<std::uint32_t>(std::max(v[k], v[(k + 1) % n]));
      owners.push_back({(std::uint64_t(a) << 32) | b, static_cast<std::uint32_t>(element)});
    }
  };
  for (size_t i = 0; i < mesh.triangles.size(); ++i) visit(int(i), mesh.triangles[i].data(), 3);
  for (size_t i = 0; i < mesh.quads.size(); ++i) visit(int(mesh.triangles.size() + i), mesh.quads[i].data(), 4);
  std::sort(owners.begin(), owners.end(),
            [](const Owner& x, const Owner& y) { return x.edge != y.edge ? x.edge < y.edge : x.element < y.element; });
  double worst = 1.0;
  for (size_t i = 0; i < owners.size();) {
    size_t j = i + 1;
    const double a = size[owners[i].element];
    for (; j < owners.size() && owners[j].edge == owners[i].edge; ++j) {
      const double b = size[owners[j].element];
      if (a > 0 && b > 0) worst = std::max(worst, std::max(a, b) / std::min(a, b));
    }
    i = j;
  }
  return worst;
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

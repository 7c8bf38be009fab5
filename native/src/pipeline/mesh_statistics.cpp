#include "anisomesh/pipeline/mesh_statistics.h"

#include <algorithm>
#include <cmath>

#include "anisomesh/mesh/element_edges.h"
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

double largestNeighbourSizeRatio(const Mesh& mesh) { return largestNeighbourSizeRatio(mesh, elementEdges(mesh)); }

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

#include "anisomesh/adapt/hessian_recovery.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/curve.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {
namespace {

using Mat5 = Eigen::Matrix<double, 5, 5>;
using Vec5 = Eigen::Matrix<double, 5, 1>;

// Vertex adjacency (CSR, sorted) and boundary flags of a triangulation.
struct Adjacency {
  std::vector<int> start, nbr;
  std::vector<char> boundary;
};

Adjacency buildAdjacency(int n, const std::vector<std::array<int, 3>>& tris) {
  std::vector<std::array<int, 2>> edges;
  edges.reserve(tris.size() * 3);
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  Adjacency adj;
  adj.boundary.assign(size_t(n), 0);
  std::vector<int> degree(size_t(n), 0);
  std::vector<std::array<int, 2>> unique;
  unique.reserve(edges.size() / 2 + 1);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) adj.boundary[size_t(edges[i][0])] = adj.boundary[size_t(edges[i][1])] = 1;
    unique.push_back(edges[i]);
    ++degree[size_t(edges[i][0])];
    ++degree[size_t(edges[i][1])];
    i = j;
  }
  adj.start.assign(size_t(n) + 1, 0);
  for (int v = 0; v < n; ++v) adj.start[size_t(v) + 1] = adj.start[size_t(v)] + degree[size_t(v)];
  adj.nbr.resize(size_t(adj.start.back()));
  std::vector<int> fill(adj.start.begin(), adj.start.end() - 1);
  for (const auto& e : unique) {
    adj.nbr[size_t(fill[size_t(e[0])]++)] = e[1];
    adj.nbr[size_t(fill[size_t(e[1])]++)] = e[0];
  }
  return adj;
}

}  // namespace

std::vector<std::array<int, 3>> meshTriangles(const Mesh& mesh) {
  std::vector<std::array<int, 3>> tris = mesh.triangles;
  for (const auto& q : mesh.quads) {
    tris.push_back({q[0], q[1], q[2]});
    tris.push_back({q[0], q[2], q[3]});
  }
  return tris;
}

void validateField(const Mesh& mesh, const std::vector<double>& field) {
  require(int(field.size()) == mesh.vertexCount(), ErrorCode::InvalidArgument,
          "field: " + std::to_string(field.size()) + " values for " + std::to_string(mesh.vertexCount()) + " vertices");
  require(mesh.elementCount() > 0, ErrorCode::InvalidArgument, "field: the mesh has no triangles or quadrilaterals");
  for (size_t i = 0; i < field.size(); ++i)
    require(
        std::isfinite(field[i]), ErrorCode::InvalidArgument,
        "field: the value at vertex " + std::to_string(i + 1) + " is not finite (" + std::to_string(field[i]) + ")");
  const int n = mesh.vertexCount();
  for (size_t i = 0; i < mesh.points.size(); ++i)
    require(mesh.points[i].z() == 0.0 && std::isfinite(mesh.points[i].x()) && std::isfinite(mesh.points[i].y()),
            ErrorCode::InvalidDomain,
            "field: vertex " + std::to_string(i + 1) + " is not a finite planar point (z = 0)");
  auto check = [&](const int* v, int k, size_t index, const char* kind) {
    double area2 = 0;
    for (int a = 0; a < k; ++a) {
      require(v[a] >= 0 && v[a] < n, ErrorCode::InvalidArgument,
              std::string("field: ") + kind + " " + std::to_string(index + 1) + " has a vertex out of range");
      const Vec3 &p = mesh.points[size_t(v[a])], &q = mesh.points[size_t(v[(a + 1) % k])];
      area2 += p.x() * q.y() - p.y() * q.x();
    }
    require(area2 > 0, ErrorCode::InvalidDomain,
            std::string("field: ") + kind + " " + std::to_string(index + 1) +
                (area2 < 0 ? " is inverted (clockwise)" : " has zero area"));
  };
  for (size_t t = 0; t < mesh.triangles.size(); ++t) check(mesh.triangles[t].data(), 3, t, "triangle");
  for (size_t q = 0; q < mesh.quads.size(); ++q) check(mesh.quads[q].data(), 4, q, "quadrilateral");
}

RecoveredDerivatives recoverHessian(const Mesh& mesh, const std::vector<double>& field,
                                    const HessianRecoveryOptions& options) {
  require(options.interiorRings >= 1 && options.boundaryRings >= 1 && options.maxRings >= 1, ErrorCode::InvalidArgument,
          "Hessian recovery: ring counts must be >= 1");
  validateField(mesh, field);
  const int n = mesh.vertexCount();
  const Adjacency adj = buildAdjacency(n, meshTriangles(mesh));
  RecoveredDerivatives out;
  out.gradient.assign(size_t(n), Vec2::Zero());
  out.hessian.assign(size_t(n), Mat2::Zero());
  out.hessianNoise.assign(size_t(n), 0.0);
  std::vector<int> stamp(size_t(n), -1);
  std::vector<int> patch;
  const double eps = std::numeric_limits<double>::epsilon();
  for (int i = 0; i < n; ++i) {
    const Vec2 xi = mesh.points[size_t(i)].head<2>();
    const int first = adj.boundary[size_t(i)] ? options.boundaryRings : options.interiorRings;
    const int last = std::max(first, options.maxRings);
    // Patch grown ring by ring: patch[0, ringEnd) are the vertices within `rings` rings.
    patch.clear();
    patch.push_back(i);
    stamp[size_t(i)] = i;
    size_t ringBegin = 0;
    bool solved = false;
    for (int rings = 1; rings <= last && !solved; ++rings) {
      const size_t ringEnd = patch.size();
      for (size_t k = ringBegin; k < ringEnd; ++k) {
        const int v = patch[k];
        for (int e = adj.start[size_t(v)]; e < adj.start[size_t(v) + 1]; ++e) {
          const int w = adj.nbr[size_t(e)];
          if (stamp[size_t(w)] != i) stamp[size_t(w)] = i, patch.push_back(w);
        }
      }
      ringBegin = ringEnd;
      if (rings < first || patch.size() < 6) continue;
      // Coordinates normalized by the patch's own spread (d' = T d with T = C^(-1/2), C the
      // covariance of the offsets): the fit's conditioning does not depend on the patch's
      // size or anisotropy. A flat C (collinear patch) grows the patch.
      double fmax = std::abs(field[size_t(i)]);
      Mat2 cov = Mat2::Zero();
      for (size_t k = 1; k < patch.size(); ++k) {
        const Vec2 d = mesh.points[size_t(patch[k])].head<2>() - xi;
        cov += d * d.transpose();
        fmax = std::max(fmax, std::abs(field[size_t(patch[k])]));
      }
      cov /= double(patch.size() - 1);
      const double tr = cov.trace();
      if (!(cov.determinant() > 1e-12 * tr * tr)) continue;
      const Mat2 t = sqrtSpd(cov).inverse();
      Mat5 a = Mat5::Zero();
      Vec5 b = Vec5::Zero();
      for (size_t k = 1; k < patch.size(); ++k) {
        const Vec2 d = t * (mesh.points[size_t(patch[k])].head<2>() - xi);
        Vec5 row;
        row << d.x(), d.y(), d.x() * d.x(), d.x() * d.y(), d.y() * d.y();
        a.selfadjointView<Eigen::Lower>().rankUpdate(row);
        b += row * (field[size_t(patch[k])] - field[size_t(i)]);
      }
      const Mat5 full = a.selfadjointView<Eigen::Lower>();
      const Eigen::LDLT<Mat5> ldlt(full);
      const Vec5 dd = ldlt.vectorD();
      const double dmax = dd.cwiseAbs().maxCoeff(), dmin = dd.minCoeff();
      if (!(dmin > 1e-10 * dmax)) continue;  // too few directions for a quadratic: grow the patch
      const Vec5 c = ldlt.solve(b);
      // q(d) = g'.d' + 1/2 d'^T H' d' with d' = T d: g = T^T g', H = T^T H' T.
      out.gradient[size_t(i)] = t.transpose() * Vec2(c[0], c[1]);
      Mat2 hp;
      hp << 2 * c[2], c[3], c[3], 2 * c[4];
      out.hessian[size_t(i)] = t.transpose() * hp * t;
      out.hessianNoise[size_t(i)] = 1e3 * eps * fmax * (t.transpose() * t).norm();
      solved = true;
    }
    require(solved, ErrorCode::InvalidArgument,
            "Hessian recovery: the patch of vertex " + std::to_string(i + 1) + " " + formatPoint(xi) +
                " does not determine a quadratic (its vertices are nearly collinear)");
  }
  return out;
}

}  // namespace anisomesh

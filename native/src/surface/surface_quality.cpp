// Surface meshing: 3D measures (model size, chord and triangle deviation from the surface,
// quad quality in a 3D metric, size ratio across shared edges).
#include "model_mesher.h"

#include "anisomesh/metric/sym_eigen.h"

namespace anisomesh {
namespace surface_mesher {

double modelSize(const SurfaceModel& m) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : m.patches) {
    const Box2 b = p.surface->domain();
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) {
        const Vec3 x = p.surface->point(b.lo + Vec2(b.size().x() * i / 4.0, b.size().y() * j / 4.0));
        if (x.allFinite()) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      }
  }
  const double d = (hi - lo).norm();
  return std::isfinite(d) && d > 0 ? d : 1.0;
}

// The gaps between the chord x0x1 and the surface at the 7 samples t = i / 8 of the
// parameter segment u0u1: along the surface normal (the edge-to-surface gap, without the
// tangential offset a curved parameter line adds), and chordDeviation()'s gap (the surface
// point's distance to the chord of the surface's own end points), bit for bit as
// chordDeviation() with 7 samples gives it: firstDerivatives(uv).p is point(uv).
EdgeChordGaps edgeChordGaps(const Surface& s, const Vec2& u0, const Vec2& u1, const Vec3& x0, const Vec3& x1) {
  const Vec3 pa = s.point(u0), pb = s.point(u1), e = pb - pa;
  const double ee = e.squaredNorm();
  EdgeChordGaps g;
  for (int i = 1; i <= 7; ++i) {
    const double t = i / 8.0;
    const SurfaceDerivatives d = s.firstDerivatives((1.0 - t) * u0 + t * u1);
    g.iso = std::max(g.iso, chordGap(d.p, pa, e, ee));
    const Vec3 n = d.su.cross(d.sv);
    if (!(n.norm() > 0)) continue;
    g.normal = std::max(g.normal, std::abs(n.normalized().dot(d.p - ((1.0 - t) * x0 + t * x1))));
  }
  return g;
}

// The same gap inside the triangle (u0, u1, u2) -> (x0, x1, x2): at the 10 interior
// barycentric points (i, j, k) / 6 (centroid included), the distance from the flat
// triangle's point to the tangent plane at the surface point of the same parameter.
double normalTriangleDeviation(const Surface& s, const Vec2 u[3], const Vec3 x[3]) {
  double worst = 0.0;
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; i + j <= 5; ++j) {
      const double a = i / 6.0, b = j / 6.0, c = 1.0 - a - b;
      const SurfaceDerivatives d = s.firstDerivatives(a * u[0] + b * u[1] + c * u[2]);
      const Vec3 n = d.su.cross(d.sv);
      if (!(n.norm() > 0)) continue;
      worst = std::max(worst, std::abs(n.normalized().dot(d.p - (a * x[0] + b * x[1] + c * x[2]))));
    }
  return worst;
}

// 3D quad quality in a constant metric: min over corners of 2 |e1 x e2|_M / (|e1|_M^2 + |e2|_M^2)
// (1 for a unit square; as metricQuadQuality in the parameter plane).
double quadQuality3D(const Vec3 x[4], const Mat3& m3) {
  double q = 1.0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 e1 = x[(k + 1) % 4] - x[k], e2 = x[(k + 3) % 4] - x[k];
    const double g11 = e1.dot(m3 * e1), g22 = e2.dot(m3 * e2), g12 = e1.dot(m3 * e2);
    const double sum = g11 + g22;
    q = std::min(q, sum > 0 ? 2.0 * std::sqrt(std::max(g11 * g22 - g12 * g12, 0.0)) / sum : 0.0);
  }
  return q;
}

}  // namespace surface_mesher

Mat3 metric3DFromParameter(const Metric& m, const SurfaceDerivatives& d) {
  const Eigen::Matrix<double, 3, 2> j = d.jacobian();
  const Mat2 g = j.transpose() * j;
  const Mat2 gi = g.inverse();
  const Eigen::Matrix<double, 2, 3> jp = gi * j.transpose();  // J+: 3D tangent vector -> (u, v)
  Mat3 t = jp.transpose() * m.tensor() * jp;
  t = 0.5 * (t + t.transpose());
  const Vec3 n = d.su.cross(d.sv);
  if (n.norm() > 0) {
    // t = J+^T M J+ has rank 2; its nonzero eigenvalues are those of M G^-1 (J+ J+^T = G^-1),
    // the same as those of the symmetric Mt G^-1 Mt: a closed form in place of a 3x3
    // iterative solve (which was most of the surface quality report's time).
    const double lmax = symEigenValues(m.transform() * gi * m.transform()).l1;
    const Vec3 nu = n.normalized();
    t += lmax * nu * nu.transpose();
  }
  return t;
}

double acrossEdgeSizeRatio(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges) {
  // Elements: triangles, then quads (index nt + q).
  const size_t nt = mesh.triangles.size();
  std::map<std::array<int, 2>, std::vector<int>> at;
  for (const auto& e : edges) at[{std::min(e[0], e[1]), std::max(e[0], e[1])}];
  auto visit = [&](const int* v, int n, int element) {
    for (int k = 0; k < n; ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      auto it = at.find({std::min(a, b), std::max(a, b)});
      if (it != at.end()) it->second.push_back(element);
    }
  };
  for (size_t t = 0; t < nt; ++t) visit(mesh.triangles[t].data(), 3, int(t));
  for (size_t t = 0; t < mesh.quads.size(); ++t) visit(mesh.quads[t].data(), 4, int(nt + t));
  auto triArea = [&](int i, int j, int k) {
    const Vec3& a = mesh.points[size_t(i)];
    return 0.5 * (mesh.points[size_t(j)] - a).cross(mesh.points[size_t(k)] - a).norm();
  };
  auto area = [&](int e) {
    if (size_t(e) < nt) {
      const auto& t = mesh.triangles[size_t(e)];
      return triArea(t[0], t[1], t[2]);
    }
    const auto& q = mesh.quads[size_t(e) - nt];
    return triArea(q[0], q[1], q[2]) + triArea(q[0], q[2], q[3]);
  };
  double worst = 0.0;
  for (const auto& e : at)
    if (e.second.size() == 2) {
      const double s0 = std::sqrt(area(e.second[0])), s1 = std::sqrt(area(e.second[1]));
      if (s0 > 0 && s1 > 0) worst = std::max(worst, std::max(s0, s1) / std::min(s0, s1));
    }
  return worst;
}

}  // namespace anisomesh

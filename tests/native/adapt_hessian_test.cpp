// Hessian recovery: exact for quadratics on any mesh (interior and boundary vertices),
// convergent for smooth fields under refinement; bad input is coded.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "adapt_test_util.h"
#include "anisomesh/adapt/hessian_recovery.h"
#include "anisomesh/core/error.h"

using namespace anisomesh;
using namespace adapttest;

namespace {

double quadratic(const Vec2& p) {
  const double x = p.x(), y = p.y();
  return 1.0 + 2.0 * x - 3.0 * y + 1.5 * x * x - 0.7 * x * y + 2.2 * y * y;
}
Mat2 quadraticHessian() {
  Mat2 h;
  h << 3.0, -0.7, -0.7, 4.4;
  return h;
}

std::vector<double> sample(const Mesh& m, double (*f)(const Vec2&)) {
  std::vector<double> v;
  for (const Vec3& p : m.points) v.push_back(f(p.head<2>()));
  return v;
}

std::vector<char> boundaryFlags(const Mesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : meshTriangles(m))
    for (int k = 0; k < 3; ++k) ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  std::vector<char> b(m.points.size(), 0);
  for (const auto& u : uses)
    if (u.second == 1) b[size_t(u.first.first)] = b[size_t(u.first.second)] = 1;
  return b;
}

void expectExact(const Mesh& m, const char* what) {
  const RecoveredDerivatives d = recoverHessian(m, sample(m, quadratic));
  const std::vector<char> bnd = boundaryFlags(m);
  int boundary = 0;
  double worst = 0;
  for (size_t i = 0; i < m.points.size(); ++i) {
    const Vec2 p = m.points[i].head<2>();
    const Vec2 g(2.0 + 3.0 * p.x() - 0.7 * p.y(), -3.0 - 0.7 * p.x() + 4.4 * p.y());
    worst = std::max(worst, (d.hessian[i] - quadraticHessian()).norm() / quadraticHessian().norm());
    worst = std::max(worst, (d.gradient[i] - g).norm() / g.norm());
    boundary += bnd[i];
  }
  EXPECT_GT(boundary, 3) << what;
  EXPECT_LT(worst, 1e-8) << what << ": largest relative error of the recovered derivatives";
}

}  // namespace

TEST(HessianRecovery, ExactForQuadraticsOnAnyMesh) {
  expectExact(gridMesh(12), "regular grid");
  expectExact(gridMesh(15, 0.6, 3.0, -1.0, 2.0), "jittered grid");
  expectExact(remeshedSquare(Metric::isotropic(0.07)), "unstructured isotropic");
  expectExact(remeshedSquare(Metric::fromSizes(0.4, 0.01, 0.2)), "unstructured anisotropic (aspect 20)");
  Mesh quads = gridMesh(6);
  quads.triangles.clear();
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) quads.quads.push_back({j * 7 + i, j * 7 + i + 1, (j + 1) * 7 + i + 1, (j + 1) * 7 + i});
  expectExact(quads, "quadrilaterals");
}

// Max error of the recovered Hessian of f = sin(2x + 1) cos(3y) on nested unstructured
// meshes of the unit square, interior and boundary vertices apart; rates in h.
TEST(HessianRecovery, ConvergesForSmoothFields) {
  auto f = [](const Vec2& p) { return std::sin(2 * p.x() + 1) * std::cos(3 * p.y()); };
  auto hess = [](const Vec2& p) {
    const double s = std::sin(2 * p.x() + 1), c = std::cos(2 * p.x() + 1), cy = std::cos(3 * p.y()),
                 sy = std::sin(3 * p.y());
    Mat2 h;
    h << -4 * s * cy, -6 * c * sy, -6 * c * sy, -9 * s * cy;
    return h;
  };
  const double hs[] = {0.08, 0.04, 0.02};
  double inner[3], outer[3], innerMean[3];
  for (int k = 0; k < 3; ++k) {
    const Mesh m = remeshedSquare(Metric::isotropic(hs[k]));
    std::vector<double> v;
    for (const Vec3& p : m.points) v.push_back(f(p.head<2>()));
    const RecoveredDerivatives d = recoverHessian(m, v);
    const std::vector<char> bnd = boundaryFlags(m);
    inner[k] = outer[k] = innerMean[k] = 0;
    int ni = 0;
    for (size_t i = 0; i < m.points.size(); ++i) {
      const double e = (d.hessian[i] - hess(m.points[i].head<2>())).norm();
      (bnd[i] ? outer[k] : inner[k]) = std::max(bnd[i] ? outer[k] : inner[k], e);
      if (!bnd[i]) innerMean[k] += e, ++ni;
    }
    innerMean[k] /= ni;
    std::cout << "h = " << hs[k] << " vertices " << m.vertexCount() << ": interior max " << inner[k] << " mean "
              << innerMean[k] << ", boundary max " << outer[k] << "\n";
  }
  const double rateInner = std::log2(inner[0] / inner[2]) / 2, rateOuter = std::log2(outer[0] / outer[2]) / 2,
               rateMean = std::log2(innerMean[0] / innerMean[2]) / 2;
  std::cout << "rates in h: interior max " << rateInner << ", interior mean " << rateMean << ", boundary max "
            << rateOuter << "\n";
  EXPECT_GT(rateInner, 0.7);
  EXPECT_GT(rateMean, 0.9);
  EXPECT_GT(rateOuter, 0.7);
  EXPECT_LT(outer[2], 0.5);  // |H| is about 10: the boundary is within 5% on the finest mesh
}

TEST(HessianRecovery, BadInputIsCoded) {
  const Mesh m = gridMesh(4);
  auto code = [&](const Mesh& mesh, const std::vector<double>& v) {
    try {
      recoverHessian(mesh, v);
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Internal;
  };
  EXPECT_EQ(code(m, std::vector<double>(m.points.size() - 1, 1.0)), ErrorCode::InvalidArgument);
  std::vector<double> v(m.points.size(), 1.0);
  v[3] = std::nan("");
  EXPECT_EQ(code(m, v), ErrorCode::InvalidArgument);
  v[3] = INFINITY;
  EXPECT_EQ(code(m, v), ErrorCode::InvalidArgument);
  Mesh noTriangles = m;
  noTriangles.triangles.clear();
  EXPECT_EQ(code(noTriangles, std::vector<double>(m.points.size(), 1.0)), ErrorCode::InvalidArgument);
  Mesh inverted = m;
  std::swap(inverted.triangles[5][0], inverted.triangles[5][1]);
  EXPECT_EQ(code(inverted, std::vector<double>(m.points.size(), 1.0)), ErrorCode::InvalidDomain);
  Mesh flat = m;
  flat.triangles[2] = {0, 1, 2};  // three points on the bottom row
  EXPECT_EQ(code(flat, std::vector<double>(m.points.size(), 1.0)), ErrorCode::InvalidDomain);
  // A constant field recovers zero exactly.
  const RecoveredDerivatives d = recoverHessian(m, std::vector<double>(m.points.size(), 7.0));
  for (const Mat2& h : d.hessian) EXPECT_EQ(h.norm(), 0.0);
}

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/surface.h"

using namespace anisomesh;

namespace {

constexpr double kPiGeometry = 3.14159265358979323846;

std::array<std::array<Vec3, 4>, 4> curvedBezierPoints() {
  std::array<std::array<Vec3, 4>, 4> cp;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      cp[i][j] = Vec3(i + 0.1 * j * j, j - 0.2 * i, std::sin(1.0 * i + 0.5 * j) + 0.3 * i * j);
  return cp;
}

std::vector<std::vector<Vec3>> curvedBSplinePoints(int m, int n) {
  std::vector<std::vector<Vec3>> cp(m, std::vector<Vec3>(n));
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) cp[i][j] = Vec3(i + 0.05 * j, j, std::cos(0.7 * i) * std::sin(0.9 * j) + 0.1 * i);
  return cp;
}

// One of every kind, curved where the kind allows.
std::vector<std::shared_ptr<Surface>> allSurfaces() {
  return {
      std::make_shared<PlaneSurface>(Vec3(1, 2, 3), Vec3(1, 0.5, 0), Vec3(0, 1, 2)),
      std::make_shared<HeightFieldSurface>("sin(u)*cos(2*v) + u*v^2", Box2{{-1, -1}, {1, 1}}),
      std::make_shared<CylinderSurface>(1.5, Vec3(0, 1, 0)),
      std::make_shared<SphereSurface>(2.0, Vec3(1, 0, 0)),
      std::make_shared<TorusSurface>(3.0, 1.0),
      std::make_shared<BezierPatchSurface>(curvedBezierPoints()),
      std::make_shared<BSplinePatchSurface>(curvedBSplinePoints(6, 7)),
      std::make_shared<BSplinePatchSurface>(curvedBSplinePoints(5, 4), 2, 3),
      std::make_shared<ExpressionSurface>("u*cos(v)", "u*sin(v)", "0.5*u^2 + v", Box2{{0.5, 0}, {2, 3}}),
      paperP2(),
  };
}

void expectVecNear(const Vec3& a, const Vec3& b, double tol, const std::string& what) {
  EXPECT_LE((a - b).norm(), tol * std::max(1.0, b.norm())) << what << ": " << a.transpose() << " vs " << b.transpose();
}

std::shared_ptr<ExpressionSurface> expressionSphere(double r) {
  const std::string R = std::to_string(r);
  return std::make_shared<ExpressionSurface>(R + "*cos(v)*cos(u)", R + "*cos(v)*sin(u)", R + "*sin(v)",
                                             Box2{{0, -1.4}, {2 * kPiGeometry, 1.4}}, "expression sphere");
}

}  // namespace

TEST(SurfaceGeometry, DerivativesOfEveryKindMatchCentralDifferences) {
  std::mt19937 rng(3);
  for (const auto& s : allSurfaces()) {
    const Box2 d = s->domain();
    const double h = 1e-6 * std::max(d.size().x(), d.size().y());
    std::uniform_real_distribution<double> tu(0.02, 0.98);
    for (int i = 0; i < 25; ++i) {
      const Vec2 uv(d.lo.x() + tu(rng) * d.size().x(), d.lo.y() + tu(rng) * d.size().y());
      const Vec2 eu(h, 0), ev(0, h);
      const SurfaceDerivatives x = s->derivatives(uv);
      expectVecNear(x.p, s->point(uv), 1e-14, s->name() + " p");
      expectVecNear(x.su, (s->point(uv + eu) - s->point(uv - eu)) / (2 * h), 1e-6, s->name() + " Su");
      expectVecNear(x.sv, (s->point(uv + ev) - s->point(uv - ev)) / (2 * h), 1e-6, s->name() + " Sv");
      const SurfaceDerivatives pu = s->derivatives(uv + eu), mu = s->derivatives(uv - eu);
      const SurfaceDerivatives pv = s->derivatives(uv + ev), mv = s->derivatives(uv - ev);
      expectVecNear(x.suu, (pu.su - mu.su) / (2 * h), 1e-6, s->name() + " Suu");
      expectVecNear(x.suv, (pv.su - mv.su) / (2 * h), 1e-6, s->name() + " Suv");
      expectVecNear(x.suv, (pu.sv - mu.sv) / (2 * h), 1e-6, s->name() + " Svu");
      expectVecNear(x.svv, (pv.sv - mv.sv) / (2 * h), 1e-6, s->name() + " Svv");
      expectVecNear(s->du(uv), x.su, 0, s->name());
      expectVecNear(s->dvv(uv), x.svv, 0, s->name());
    }
  }
}

TEST(SurfaceGeometry, PrincipalDirectionsAreConsistent) {
  std::mt19937 rng(5);
  for (const auto& s : allSurfaces()) {
    const Box2 d = s->domain();
    std::uniform_real_distribution<double> tu(0.0, 1.0);
    for (int i = 0; i < 20; ++i) {
      const Vec2 uv(d.lo.x() + tu(rng) * d.size().x(), d.lo.y() + tu(rng) * d.size().y());
      const SurfaceCurvature c = curvature(*s, uv);
      const SurfaceDerivatives x = s->derivatives(uv);
      EXPECT_GE(c.k1, c.k2);
      EXPECT_NEAR(c.dir1.norm(), 1, 1e-12) << s->name();
      EXPECT_NEAR(c.dir2.norm(), 1, 1e-12) << s->name();
      EXPECT_NEAR(c.dir1.dot(c.dir2), 0, 1e-10) << s->name();
      expectVecNear(c.dir1.cross(c.dir2), c.normal, 1e-10, s->name() + " frame orientation");
      expectVecNear(c.dir1, x.su * c.uvDir1.x() + x.sv * c.uvDir1.y(), 1e-12, s->name() + " J d1");
      // II d_i = k_i G d_i.
      const double scale = c.second.norm() + std::abs(c.k1) * c.first.norm() + 1e-300;
      EXPECT_LT((c.second * c.uvDir1 - c.k1 * c.first * c.uvDir1).norm(), 1e-9 * scale) << s->name();
      EXPECT_LT((c.second * c.uvDir2 - c.k2 * c.first * c.uvDir2).norm(), 1e-9 * scale) << s->name();
      EXPECT_NEAR(c.gaussian, c.k1 * c.k2, 1e-12 * (1 + std::abs(c.gaussian)));
      EXPECT_NEAR(c.mean, 0.5 * (c.k1 + c.k2), 1e-12 * (1 + std::abs(c.mean)));
      EXPECT_LT((firstFundamentalForm(*s, uv) - c.first).norm(), 1e-14 * (1 + c.first.norm()));
      EXPECT_LT((secondFundamentalForm(*s, uv) - c.second).norm(), 1e-14 * (1 + c.second.norm()));
      expectVecNear(unitNormal(*s, uv), c.normal, 1e-15, s->name());
    }
  }
}

TEST(SurfaceGeometry, SphereCurvatureIsMinusOneOverRadiusWithOutwardNormal) {
  const double R = 2.5;
  const SphereSurface s(R, Vec3(1, -2, 0.5));
  for (double u : {0.0, 1.0, 4.0})
    for (double v : {-1.3, 0.0, 0.7}) {
      const SurfaceCurvature c = curvature(s, {u, v});
      EXPECT_NEAR(c.k1, -1 / R, 1e-13);
      EXPECT_NEAR(c.k2, -1 / R, 1e-13);
      EXPECT_NEAR(c.gaussian, 1 / (R * R), 1e-13);
      EXPECT_NEAR(c.mean, -1 / R, 1e-13);
      EXPECT_NEAR(c.normal.dot((s.point({u, v}) - Vec3(1, -2, 0.5)) / R), 1, 1e-13);
    }
}

TEST(SurfaceGeometry, CylinderCurvatureIsZeroAxiallyAndOneOverRadiusAround) {
  const double R = 0.8;
  const CylinderSurface s(R);
  const SurfaceCurvature c = curvature(s, {0.4, 0.3});
  EXPECT_NEAR(c.k1, 0, 1e-14);
  EXPECT_NEAR(c.k2, -1 / R, 1e-14);
  EXPECT_NEAR(std::abs(c.dir1.z()), 1, 1e-12);  // zero curvature along the axis
  EXPECT_NEAR(c.dir2.z(), 0, 1e-12);
  EXPECT_NEAR(c.gaussian, 0, 1e-14);
}

TEST(SurfaceGeometry, TorusCurvatureAtEquators) {
  const double R = 3, r = 1;
  const TorusSurface s(R, r);
  const SurfaceCurvature outer = curvature(s, {0.3, 0.0});
  EXPECT_NEAR(outer.k1, -1 / (R + r), 1e-13);  // along the parallel
  EXPECT_NEAR(outer.k2, -1 / r, 1e-13);        // along the meridian
  EXPECT_GT(outer.gaussian, 0);
  const SurfaceCurvature inner = curvature(s, {1.1, kPiGeometry});
  EXPECT_NEAR(inner.k1, 1 / (R - r), 1e-13);  // saddle: the parallel bends the other way
  EXPECT_NEAR(inner.k2, -1 / r, 1e-13);
  EXPECT_LT(inner.gaussian, 0);
  // General latitude: k_parallel = cos v / (R + r cos v).
  const double v = 0.9;
  const SurfaceCurvature mid = curvature(s, {2.0, v});
  EXPECT_NEAR(mid.k1, -std::cos(v) / (R + r * std::cos(v)), 1e-13);
  EXPECT_NEAR(mid.k2, -1 / r, 1e-13);
}

TEST(SurfaceGeometry, PlaneHasZeroCurvature) {
  const PlaneSurface s(Vec3(0, 0, 1), Vec3(2, 0, 0), Vec3(1, 1, 0), Box2{{-1, -1}, {1, 1}});
  const SurfaceCurvature c = curvature(s, {0.3, -0.2});
  EXPECT_EQ(c.k1, 0);
  EXPECT_EQ(c.k2, 0);
  expectVecNear(c.normal, Vec3(0, 0, 1), 1e-15, "plane normal");
}

TEST(SurfaceGeometry, BezierAndBSplinePatchesOfAPlaneArePlanar) {
  const Vec3 o(1, 2, 3), a(1, 0.2, 0.5), b(-0.3, 1, 0.4);
  const Vec3 n = a.cross(b).normalized();
  std::array<std::array<Vec3, 4>, 4> bez;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)  // uneven in-plane spacing: still planar
      bez[i][j] = o + (i + 0.2 * std::sin(3.0 * j)) * a + (j * j * 0.5 + 0.1 * i) * b;
  std::vector<std::vector<Vec3>> bsp(6, std::vector<Vec3>(5));
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 5; ++j) bsp[i][j] = o + (i + 0.3 * std::cos(1.0 * i * j)) * a + (1.0 * j + 0.1 * i * i) * b;
  const BezierPatchSurface sb(bez);
  const BSplinePatchSurface ss(bsp);
  for (const Surface* s : {static_cast<const Surface*>(&sb), static_cast<const Surface*>(&ss)})
    for (double u = 0; u <= 1.0; u += 0.125)
      for (double v = 0; v <= 1.0; v += 0.125) {
        EXPECT_NEAR(n.dot(s->point({u, v}) - o), 0, 1e-13) << s->name();
        const SurfaceCurvature c = curvature(*s, {u, v});
        EXPECT_NEAR(std::abs(c.normal.dot(n)), 1, 1e-12) << s->name();
        EXPECT_NEAR(c.k1, 0, 1e-12) << s->name();
        EXPECT_NEAR(c.k2, 0, 1e-12) << s->name();
      }
}

TEST(SurfaceGeometry, BSplineWithFourByFourPointsIsTheBezierPatch) {
  const auto cp = curvedBezierPoints();
  std::vector<std::vector<Vec3>> rows;
  for (const auto& r : cp) rows.emplace_back(r.begin(), r.end());
  const BezierPatchSurface bez(cp);
  const BSplinePatchSurface bsp(rows);
  for (double u : {0.0, 0.3, 0.77, 1.0})
    for (double v : {0.0, 0.5, 1.0}) {
      const SurfaceDerivatives a = bez.derivatives({u, v}), b = bsp.derivatives({u, v});
      expectVecNear(b.p, a.p, 1e-13, "p");
      expectVecNear(b.su, a.su, 1e-13, "su");
      expectVecNear(b.svv, a.svv, 1e-12, "svv");
      expectVecNear(b.suv, a.suv, 1e-12, "suv");
    }
  // Clamped: corners interpolate the corner control points.
  expectVecNear(bsp.point({0, 0}), cp[0][0], 1e-15, "corner");
  expectVecNear(bsp.point({1, 1}), cp[3][3], 1e-15, "corner");
}

TEST(SurfaceGeometry, ExpressionSphereMatchesSphereClass) {
  const double R = 1.7;
  const SphereSurface sphere(R);
  const auto expr = expressionSphere(R);
  for (double u : {0.1, 2.0, 5.5})
    for (double v : {-1.2, 0.0, 0.9}) {
      const SurfaceDerivatives a = sphere.derivatives({u, v}), b = expr->derivatives({u, v});
      expectVecNear(b.p, a.p, 1e-12, "p");
      expectVecNear(b.su, a.su, 1e-12, "su");
      expectVecNear(b.sv, a.sv, 1e-12, "sv");
      expectVecNear(b.suu, a.suu, 1e-12, "suu");
      expectVecNear(b.suv, a.suv, 1e-12, "suv");
      expectVecNear(b.svv, a.svv, 1e-12, "svv");
      const SurfaceCurvature c = curvature(*expr, {u, v});
      EXPECT_NEAR(c.k1, -1 / R, 1e-10);
      EXPECT_NEAR(c.k2, -1 / R, 1e-10);
    }
}

TEST(SurfaceGeometry, PaperP2IsTheHeightField) {
  const auto p2 = paperP2();
  EXPECT_EQ(p2->name(), "p2");
  EXPECT_EQ(p2->domain().lo, Vec2(-10, -10));
  EXPECT_EQ(p2->domain().hi, Vec2(10, 10));
  const HeightFieldSurface h("1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)", p2->domain());
  for (double u : {-9.5, -1.0, 3.3})
    for (double v : {-7.0, 0.2, 9.9}) {
      const double z = 1.5 * std::exp(-0.001 * (u * u + v * v)) * std::sin(2 * u) * std::cos(0.2 * v);
      expectVecNear(p2->point({u, v}), Vec3(u, v, z), 1e-15, "p2");
      expectVecNear(p2->derivatives({u, v}).suv, h.derivatives({u, v}).suv, 1e-15, "p2 suv");
    }
}

TEST(SurfaceGeometry, DegeneratePointThrowsInvalidSurfaceNamingThePoint) {
  const SphereSurface s(1.0, Vec3::Zero(), Box2{{0, -kPiGeometry / 2}, {2 * kPiGeometry, kPiGeometry / 2}});
  EXPECT_TRUE(isDegenerate(s.derivatives({0.5, kPiGeometry / 2})));
  EXPECT_FALSE(isDegenerate(s.derivatives({0.5, 1.5})));
  try {
    curvature(s, {0.5, kPiGeometry / 2});
    ADD_FAILURE() << "expected InvalidSurface";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidSurface);
    const std::string m = e.what();
    EXPECT_NE(m.find("surface 'sphere' at (u, v) = (0.5, 1.570796327)"), std::string::npos) << m;
    EXPECT_NE(m.find("degenerate"), std::string::npos) << m;
  }
  EXPECT_THROW(unitNormal(s, {0.5, -kPiGeometry / 2}), Error);
}

TEST(SurfaceGeometry, NonFiniteExpressionThrowsInvalidSurface) {
  const ExpressionSurface s("u", "v", "sqrt(u)", Box2{{-1, 0}, {1, 1}}, "root");
  try {
    s.derivatives({-0.5, 0.25});
    ADD_FAILURE() << "expected InvalidSurface";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidSurface);
    const std::string m = e.what();
    EXPECT_NE(m.find("z(u,v) = sqrt(u)"), std::string::npos) << m;
    EXPECT_NE(m.find("surface 'root' at (u, v) = (-0.5, 0.25)"), std::string::npos) << m;
  }
  EXPECT_THROW(s.point({-0.5, 0.25}), Error);
  // sqrt at 0 has an infinite derivative.
  EXPECT_THROW(s.derivatives({0.0, 0.25}), Error);
  EXPECT_NO_THROW(s.derivatives({0.5, 0.25}));
}

TEST(SurfaceGeometry, BadInputsAreTypedErrors) {
  auto code = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Internal;
  };
  EXPECT_EQ(code([] { ExpressionSurface("u", "v)", "0", Box2{{0, 0}, {1, 1}}); }), ErrorCode::ParseError);
  try {
    ExpressionSurface("u", "v", "sin(u))", Box2{{0, 0}, {1, 1}});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("z(u,v): unexpected ')' at column 7"), std::string::npos) << e.what();
  }
  EXPECT_EQ(code([] { SphereSurface(-1); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(code([] { TorusSurface(1, 2); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(code([] { CylinderSurface(0); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(code([] { SphereSurface(1, Vec3::Zero(), Box2{{1, 0}, {0, 1}}); }), ErrorCode::InvalidDomain);
  // Angle ranges that fold the surface over itself: past a pole, more than one turn.
  EXPECT_EQ(code([] { SphereSurface(1, Vec3::Zero(), Box2{{0, -1}, {6, 2.5}}); }), ErrorCode::InvalidDomain);
  EXPECT_EQ(code([] { SphereSurface(1, Vec3::Zero(), Box2{{0, -1.6}, {6, 1}}); }), ErrorCode::InvalidDomain);
  EXPECT_EQ(code([] { SphereSurface(1, Vec3::Zero(), Box2{{-1, 0}, {6, 1}}); }), ErrorCode::InvalidDomain);
  EXPECT_EQ(code([] { TorusSurface(2, 1, Vec3::Zero(), Box2{{0, 0}, {7, 1}}); }), ErrorCode::InvalidDomain);
  EXPECT_EQ(code([] { TorusSurface(2, 1, Vec3::Zero(), Box2{{0, -4}, {1, 3}}); }), ErrorCode::InvalidDomain);
  EXPECT_EQ(code([] { CylinderSurface(1, Vec3::Zero(), Box2{{0, 0}, {6.5, 1}}); }), ErrorCode::InvalidDomain);
  // The whole sphere (poles included) and exactly one turn are valid.
  EXPECT_EQ(code([] {
              SphereSurface(1, Vec3::Zero(), Box2{{0, -M_PI / 2}, {2 * M_PI, M_PI / 2}});
            }),
            ErrorCode::Internal);
  EXPECT_EQ(code([] { TorusSurface(2, 1, Vec3::Zero(), Box2{{-M_PI, -M_PI}, {M_PI, M_PI}}); }), ErrorCode::Internal);
  EXPECT_EQ(code([] { PlaneSurface(Vec3::Zero(), Vec3(1, 0, 0), Vec3(2, 0, 0)); }), ErrorCode::InvalidSurface);
  EXPECT_EQ(code([] { BSplinePatchSurface(curvedBSplinePoints(3, 5)); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(code([] { BSplinePatchSurface(curvedBSplinePoints(5, 5), 0, 3); }), ErrorCode::InvalidArgument);
}

TEST(SurfaceGeometry, HeightFieldCurvatureMatchesGraphFormulas) {
  // For z = f(u, v): K = (fuu fvv - fuv^2) / W^4 and
  // H = ((1 + fv^2) fuu - 2 fu fv fuv + (1 + fu^2) fvv) / (2 W^3), W^2 = 1 + fu^2 + fv^2,
  // with the upward normal (-fu, -fv, 1) / W, which is Su x Sv / |Su x Sv| here.
  const auto p2 = paperP2();
  const Expression f = Expression::parse("1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)");
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> t(-10, 10);
  for (int i = 0; i < 200; ++i) {
    const double u = t(rng), v = t(rng);
    const Dual2 z = f.evaluate(u, v);
    const double w2 = 1 + z.fu * z.fu + z.fv * z.fv, w = std::sqrt(w2);
    const double K = (z.fuu * z.fvv - z.fuv * z.fuv) / (w2 * w2);
    const double H = ((1 + z.fv * z.fv) * z.fuu - 2 * z.fu * z.fv * z.fuv + (1 + z.fu * z.fu) * z.fvv) / (2 * w2 * w);
    const SurfaceCurvature c = curvature(*p2, {u, v});
    EXPECT_NEAR(c.gaussian, K, 1e-12 * (1 + std::abs(K)));
    EXPECT_NEAR(c.mean, H, 1e-12 * (1 + std::abs(H)));
    expectVecNear(c.normal, Vec3(-z.fu, -z.fv, 1) / w, 1e-14, "p2 normal");
  }
}

// The chord measures take the surface point of a sample from firstDerivatives(uv).p instead
// of evaluating point(uv) again: both must give the same bits on every kind of surface.
TEST(SurfaceGeometry, FirstDerivativesPointIsThePointBitForBit) {
  std::vector<std::shared_ptr<Surface>> surfaces = {
      std::make_shared<PlaneSurface>(Vec3(0.1, 0.2, 0.3), Vec3(1, 0.5, 0), Vec3(0, 1, 0.25)),
      std::make_shared<HeightFieldSurface>("0.3*sin(2*u)*cos(3*v) + u^2/7", Box2{{-1, -1}, {1, 1}}),
      std::make_shared<CylinderSurface>(1.3),
      std::make_shared<SphereSurface>(0.7),
      std::make_shared<TorusSurface>(2.0, 0.5),
      std::make_shared<BezierPatchSurface>(curvedBezierPoints()),
      std::make_shared<BSplinePatchSurface>(curvedBSplinePoints(6, 5)),
      std::make_shared<ExpressionSurface>("u*cos(v)", "u*sin(v)", "0.2*exp(-u)*atan2(v, 1 + u)",
                                          Box2{{0.1, 0}, {2, 3}}),
      paperP2(),
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const auto& s : surfaces) {
    const Box2 b = s->domain();
    for (int k = 0; k < 2000; ++k) {
      const Vec2 uv = b.lo + Vec2(unit(rng) * b.size().x(), unit(rng) * b.size().y());
      const Vec3 p = s->point(uv), q = s->firstDerivatives(uv).p;
      ASSERT_TRUE(p.x() == q.x() && p.y() == q.y() && p.z() == q.z())
          << s->name() << " at (" << uv.x() << ", " << uv.y() << "): " << p.transpose() << " vs " << q.transpose();
    }
  }
}

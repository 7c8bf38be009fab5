#pragma once
// Parametric surface patches S(u, v) over a parameter box, and the differential
// geometry the surface metric needs (paper section 3: the initial control space of a
// patch comes from its principal curvatures; meshing happens in the (u, v) plane).
//
// Conventions:
// - J = [Su Sv] (3x2) is the Jacobian; G = J^T J the first fundamental form.
// - The normal is n = (Su x Sv) / |Su x Sv|; the second fundamental form is
//   II = [Suu.n, Suv.n; Suv.n, Svv.n]; principal curvatures are the eigenvalues of
//   G^-1 II, k1 >= k2 (algebraic). With this sign convention a sphere with the
//   outward normal has k1 = k2 = -1/R.
// - A point where |Su x Sv| <= 1e-10 (|Su|^2 + |Sv|^2)/2 (e.g. a sphere pole) is
//   degenerate: whatever needs the normal throws Error(InvalidSurface) naming the
//   surface and the (u, v) point.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>  // cross products

#include "anisomesh/core/types.h"
#include "anisomesh/geometry/expression.h"

namespace anisomesh {

// Point and partial derivatives up to second order at one (u, v).
struct SurfaceDerivatives {
  Vec3 p = Vec3::Zero();
  Vec3 su = Vec3::Zero(), sv = Vec3::Zero();
  Vec3 suu = Vec3::Zero(), suv = Vec3::Zero(), svv = Vec3::Zero();
  // J = [Su Sv].
  Eigen::Matrix<double, 3, 2> jacobian() const;
  // G = J^T J.
  Mat2 firstFundamentalForm() const;
};

// A parametric patch S: domain() -> R^3.
class Surface {
 public:
  Surface(std::string name, const Box2& domain);
  virtual ~Surface() = default;

  // S(u, v).
  virtual Vec3 point(const Vec2& uv) const = 0;
  // S and its derivatives up to second order; throws InvalidSurface on NaN/infinite values.
  virtual SurfaceDerivatives derivatives(const Vec2& uv) const = 0;
  // S, Su and Sv with the bits derivatives() gives them, for measures that need no
  // curvature; surfaces that can skip the second derivatives leave them zero and check
  // only S, Su, Sv for NaN/infinite values (throws InvalidSurface).
  virtual SurfaceDerivatives firstDerivatives(const Vec2& uv) const { return derivatives(uv); }
  // A text naming the surface exactly (kind, name, domain and parameters as exact bits),
  // or "" for a surface without one: equal non-empty identities mean surfaces that give
  // the same bits everywhere (and the same messages), so results may be reused.
  virtual std::string identity() const { return ""; }

  // Su.
  Vec3 du(const Vec2& uv) const { return derivatives(uv).su; }
  // Sv.
  Vec3 dv(const Vec2& uv) const { return derivatives(uv).sv; }
  // Suu.
  Vec3 duu(const Vec2& uv) const { return derivatives(uv).suu; }
  // Suv.
  Vec3 duv(const Vec2& uv) const { return derivatives(uv).suv; }
  // Svv.
  Vec3 dvv(const Vec2& uv) const { return derivatives(uv).svv; }

  // The parameter rectangle the patch is defined on.
  const Box2& domain() const { return domain_; }
  // Name used in error messages ("sphere", "p2", ...).
  const std::string& name() const { return name_; }
  // Changes the parameter rectangle; throws InvalidDomain if empty or not finite.
  void setDomain(const Box2& domain);

  // "surface 'name' at (u, v) = (0.5, 1.2)": the tail of every error about a point.
  std::string where(const Vec2& uv) const;

 protected:
  // Throws InvalidSurface unless every entry of d is finite.
  void checkFinite(const SurfaceDerivatives& d, const Vec2& uv) const;

 private:
  std::string name_;
  Box2 domain_;
};

// origin + u a1 + v a2 over domain (default [0,1]^2).
class PlaneSurface : public Surface {
 public:
  PlaneSurface(const Vec3& origin, const Vec3& a1, const Vec3& a2, const Box2& domain = {{0, 0}, {1, 1}});
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;

 private:
  Vec3 o_, a1_, a2_;
};

// Graph z = f(u, v): S = (u, v, f(u, v)).
class HeightFieldSurface : public Surface {
 public:
  HeightFieldSurface(Expression f, const Box2& domain, std::string name = "height field");
  // Parses f with the error prefix "z(u,v)".
  HeightFieldSurface(const std::string& f, const Box2& domain, std::string name = "height field");
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;
  SurfaceDerivatives firstDerivatives(const Vec2& uv) const override;

 private:
  Expression f_;
};

// Cylinder of radius R around the axis through center along z:
// S = center + (R cos u, R sin u, v). Default domain u in [0, 2 pi], v in [0, 1].
class CylinderSurface : public Surface {
 public:
  explicit CylinderSurface(double radius, const Vec3& center = Vec3::Zero(),
                           const Box2& domain = {{0.0, 0.0}, {6.283185307179586, 1.0}});
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;
  double radius() const { return r_; }

 private:
  double r_;
  Vec3 c_;
};

// Sphere of radius R, u = longitude, v = latitude:
// S = center + R (cos v cos u, cos v sin u, sin v). The poles v = +-pi/2 are degenerate,
// so the default domain stops at |v| <= 1.4 (about 80 degrees): u in [0, 2 pi].
class SphereSurface : public Surface {
 public:
  explicit SphereSurface(double radius, const Vec3& center = Vec3::Zero(),
                         const Box2& domain = {{0.0, -1.4}, {6.283185307179586, 1.4}});
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;
  double radius() const { return r_; }

 private:
  double r_;
  Vec3 c_;
};

// Torus with major radius R > minor radius r, axis z:
// S = center + ((R + r cos v) cos u, (R + r cos v) sin u, r sin v), domain [0, 2 pi]^2.
// v = 0 is the outer equator, v = pi the inner one.
class TorusSurface : public Surface {
 public:
  TorusSurface(double majorRadius, double minorRadius, const Vec3& center = Vec3::Zero(),
               const Box2& domain = {{0.0, 0.0}, {6.283185307179586, 6.283185307179586}});
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;

 private:
  double R_, r_;
  Vec3 c_;
};

// Bicubic Bezier patch on [0,1]^2; control point (i, j) multiplies B_i(u) B_j(v).
class BezierPatchSurface : public Surface {
 public:
  explicit BezierPatchSurface(const std::array<std::array<Vec3, 4>, 4>& controlPoints,
                              std::string name = "bezier patch");
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;

 private:
  std::array<std::array<Vec3, 4>, 4> cp_;
};

// Clamped uniform tensor-product B-spline patch on [0,1]^2 of degree (p, q) (default
// bicubic) with m x n control points (m >= p + 1, n >= q + 1); controlPoints[i][j]
// multiplies N_i(u) N_j(v). With m = p + 1 it reduces to a Bezier patch.
class BSplinePatchSurface : public Surface {
 public:
  BSplinePatchSurface(std::vector<std::vector<Vec3>> controlPoints, int degreeU = 3, int degreeV = 3,
                      std::string name = "b-spline patch");
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;

 private:
  std::vector<std::vector<Vec3>> cp_;
  int p_, q_;
  std::vector<double> ku_, kv_;  // clamped uniform knot vectors
};

// S = (x(u, v), y(u, v), z(u, v)) from three formulas; derivatives are exact (dual numbers).
class ExpressionSurface : public Surface {
 public:
  ExpressionSurface(Expression x, Expression y, Expression z, const Box2& domain,
                    std::string name = "expression surface");
  // Parses the three formulas with the error prefixes "x(u,v)", "y(u,v)", "z(u,v)".
  ExpressionSurface(const std::string& x, const std::string& y, const std::string& z, const Box2& domain,
                    std::string name = "expression surface");
  Vec3 point(const Vec2& uv) const override;
  SurfaceDerivatives derivatives(const Vec2& uv) const override;
  std::string identity() const override;
  SurfaceDerivatives firstDerivatives(const Vec2& uv) const override;

 private:
  std::array<Expression, 3> f_;
};

// The paper's analytic surface (fig. 10):
// p2(u, v) = (u, v, 1.5 exp(-0.001 (u^2 + v^2)) sin(2u) cos(0.2v)).
// Domain [-10, 10]^2: about six periods of sin(2u) across u and one of cos(0.2v)
// across v, with the amplitude damped to 1.5 e^-0.2 = 1.23 at the corners.
std::shared_ptr<ExpressionSurface> paperP2(const Box2& domain = {{-10.0, -10.0}, {10.0, 10.0}});

// --- differential geometry ---------------------------------------------------------

// Everything the curvature metric needs at one point.
struct SurfaceCurvature {
  Vec3 normal = Vec3::UnitZ();                          // unit normal (Su x Sv) / |Su x Sv|
  Mat2 first = Mat2::Identity();                        // G
  Mat2 second = Mat2::Zero();                           // II
  double k1 = 0.0, k2 = 0.0;                            // principal curvatures, k1 >= k2
  Vec3 dir1 = Vec3::UnitX(), dir2 = Vec3::UnitY();      // unit 3D principal directions, dir1 x dir2 = normal
  Vec2 uvDir1 = Vec2::UnitX(), uvDir2 = Vec2::UnitY();  // the same in (u, v): J uvDir_i = dir_i
  double gaussian = 0.0;                                // K = k1 k2
  double mean = 0.0;                                    // H = (k1 + k2) / 2
};

// G = [Su.Su, Su.Sv; Sv.Su, Sv.Sv] at uv.
Mat2 firstFundamentalForm(const Surface& s, const Vec2& uv);
// Unit normal; throws InvalidSurface at a degenerate point.
Vec3 unitNormal(const Surface& s, const Vec2& uv);
// II = [Suu.n, Suv.n; Suv.n, Svv.n]; throws InvalidSurface at a degenerate point.
Mat2 secondFundamentalForm(const Surface& s, const Vec2& uv);
// Principal curvatures and directions, Gaussian and mean curvature; throws InvalidSurface at a degenerate point.
SurfaceCurvature curvature(const Surface& s, const Vec2& uv);
// Same from already evaluated derivatives (the caller names the point for errors).
SurfaceCurvature curvature(const SurfaceDerivatives& d, const Surface& s, const Vec2& uv);
// True when |Su x Sv| is too small for a normal (see the header comment).
bool isDegenerate(const SurfaceDerivatives& d);

}  // namespace anisomesh

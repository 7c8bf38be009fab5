#include "anisomesh/geometry/surface.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {

namespace {

std::string fmtParam(double x) {
  std::ostringstream os;
  os << std::setprecision(10) << x;
  return os.str();
}

bool finite(const Vec3& v) { return v.allFinite(); }

// Division defined as 0 when the denominator is 0 (repeated knots make 0/0 terms).
inline double safeDiv(double a, double b) { return b == 0.0 ? 0.0 : a / b; }

// An angle parameter of an analytic surface spans at most one turn (more covers the surface
// twice: it folds over itself).
void requireOneTurn(const std::string& kind, const char* param, double lo, double hi) {
  if (hi - lo > 2.0 * M_PI * (1.0 + 1e-12))
    throw Error(ErrorCode::InvalidDomain, "surface '" + kind + "': the " + param + " range [" + fmtParam(lo) + ", " +
                                              fmtParam(hi) +
                                              "] spans more than 2 pi (the surface would fold over itself)");
}

}  // namespace

// --- SurfaceDerivatives ----------------------------------------------------------------

Eigen::Matrix<double, 3, 2> SurfaceDerivatives::jacobian() const {
  Eigen::Matrix<double, 3, 2> j;
  j.col(0) = su;
  j.col(1) = sv;
  return j;
}

Mat2 SurfaceDerivatives::firstFundamentalForm() const {
  Mat2 g;
  g(0, 0) = su.dot(su);
  g(0, 1) = g(1, 0) = su.dot(sv);
  g(1, 1) = sv.dot(sv);
  return g;
}

// --- Surface -----------------------------------------------------------------------------

Surface::Surface(std::string name, const Box2& domain) : name_(std::move(name)) { setDomain(domain); }

void Surface::setDomain(const Box2& domain) {
  if (!(domain.lo.allFinite() && domain.hi.allFinite() && domain.lo.x() < domain.hi.x() &&
        domain.lo.y() < domain.hi.y()))
    throw Error(ErrorCode::InvalidDomain, "surface '" + name_ + "': parameter domain [" + fmtParam(domain.lo.x()) +
                                              ", " + fmtParam(domain.hi.x()) + "] x [" + fmtParam(domain.lo.y()) +
                                              ", " + fmtParam(domain.hi.y()) + "] is empty or not finite");
  domain_ = domain;
}

std::string Surface::where(const Vec2& uv) const {
  return "surface '" + name_ + "' at (u, v) = (" + fmtParam(uv.x()) + ", " + fmtParam(uv.y()) + ")";
}

void Surface::checkFinite(const SurfaceDerivatives& d, const Vec2& uv) const {
  if (!(finite(d.p) && finite(d.su) && finite(d.sv) && finite(d.suu) && finite(d.suv) && finite(d.svv)))
    throw Error(ErrorCode::InvalidSurface, "NaN or infinite point or derivative on " + where(uv));
}

// --- Plane -------------------------------------------------------------------------------

PlaneSurface::PlaneSurface(const Vec3& origin, const Vec3& a1, const Vec3& a2, const Box2& domain)
    : Surface("plane", domain), o_(origin), a1_(a1), a2_(a2) {
  if (!(origin.allFinite() && a1.allFinite() && a2.allFinite() && a1.cross(a2).norm() > 0.0))
    throw Error(ErrorCode::InvalidSurface, "surface 'plane': axes must be finite and not parallel");
}

Vec3 PlaneSurface::point(const Vec2& uv) const { return o_ + uv.x() * a1_ + uv.y() * a2_; }

SurfaceDerivatives PlaneSurface::derivatives(const Vec2& uv) const {
  SurfaceDerivatives d;
  d.p = point(uv);
  d.su = a1_;
  d.sv = a2_;
  checkFinite(d, uv);
  return d;
}

// --- Height field ------------------------------------------------------------------------

HeightFieldSurface::HeightFieldSurface(Expression f, const Box2& domain, std::string name)
    : Surface(std::move(name), domain), f_(std::move(f)) {}

HeightFieldSurface::HeightFieldSurface(const std::string& f, const Box2& domain, std::string name)
    : HeightFieldSurface(Expression::parse(f, ExpressionOptions{"z(u,v)", {}}), domain, std::move(name)) {}

Vec3 HeightFieldSurface::point(const Vec2& uv) const {
  Vec3 p(uv.x(), uv.y(), f_.value(uv.x(), uv.y()));
  if (!(p.allFinite())) throw Error(ErrorCode::InvalidSurface, "z(u,v) is NaN or infinite on " + where(uv));
  return p;
}

SurfaceDerivatives HeightFieldSurface::derivatives(const Vec2& uv) const {
  const Dual2 z = f_.evaluate(uv.x(), uv.y());
  SurfaceDerivatives d;
  d.p = Vec3(uv.x(), uv.y(), z.f);
  d.su = Vec3(1, 0, z.fu);
  d.sv = Vec3(0, 1, z.fv);
  d.suu = Vec3(0, 0, z.fuu);
  d.suv = Vec3(0, 0, z.fuv);
  d.svv = Vec3(0, 0, z.fvv);
  checkFinite(d, uv);
  return d;
}

SurfaceDerivatives HeightFieldSurface::firstDerivatives(const Vec2& uv) const {
  const Dual1 z = f_.evaluateFirst(uv.x(), uv.y());
  SurfaceDerivatives d;
  d.p = Vec3(uv.x(), uv.y(), z.f);
  d.su = Vec3(1, 0, z.fu);
  d.sv = Vec3(0, 1, z.fv);
  checkFinite(d, uv);
  return d;
}

// --- Cylinder ------------------------------------------------------------------------------

CylinderSurface::CylinderSurface(double radius, const Vec3& center, const Box2& domain)
    : Surface("cylinder", domain), r_(radius), c_(center) {
  if (!(std::isfinite(radius) && radius > 0.0 && center.allFinite()))
    throw Error(ErrorCode::InvalidArgument,
                "surface 'cylinder': radius must be finite and positive, got " + fmtParam(radius));
  requireOneTurn("cylinder", "u (angle)", domain.lo.x(), domain.hi.x());
}

Vec3 CylinderSurface::point(const Vec2& uv) const {
  return c_ + Vec3(r_ * pm::cos(uv.x()), r_ * pm::sin(uv.x()), uv.y());
}

SurfaceDerivatives CylinderSurface::derivatives(const Vec2& uv) const {
  const double cu = pm::cos(uv.x()), su = pm::sin(uv.x());
  SurfaceDerivatives d;
  d.p = c_ + Vec3(r_ * cu, r_ * su, uv.y());
  d.su = Vec3(-r_ * su, r_ * cu, 0);
  d.sv = Vec3(0, 0, 1);
  d.suu = Vec3(-r_ * cu, -r_ * su, 0);
  checkFinite(d, uv);
  return d;
}

// --- Sphere --------------------------------------------------------------------------------

SphereSurface::SphereSurface(double radius, const Vec3& center, const Box2& domain)
    : Surface("sphere", domain), r_(radius), c_(center) {
  if (!(std::isfinite(radius) && radius > 0.0 && center.allFinite()))
    throw Error(ErrorCode::InvalidArgument,
                "surface 'sphere': radius must be finite and positive, got " + fmtParam(radius));
  requireOneTurn("sphere", "u (longitude)", domain.lo.x(), domain.hi.x());
  // Past a pole the latitude folds the surface back over itself.
  const double pole = 0.5 * M_PI * (1.0 + 1e-12);
  if (domain.lo.y() < -pole || domain.hi.y() > pole)
    throw Error(ErrorCode::InvalidDomain, "surface 'sphere': the v (latitude) range [" + fmtParam(domain.lo.y()) +
                                              ", " + fmtParam(domain.hi.y()) +
                                              "] passes a pole (it must lie within [-pi/2, pi/2])");
}

Vec3 SphereSurface::point(const Vec2& uv) const {
  const double cu = pm::cos(uv.x()), su = pm::sin(uv.x()), cv = pm::cos(uv.y()), sv = pm::sin(uv.y());
  return c_ + r_ * Vec3(cv * cu, cv * su, sv);
}

SurfaceDerivatives SphereSurface::derivatives(const Vec2& uv) const {
  const double cu = pm::cos(uv.x()), su = pm::sin(uv.x()), cv = pm::cos(uv.y()), sv = pm::sin(uv.y());
  SurfaceDerivatives d;
  d.p = c_ + r_ * Vec3(cv * cu, cv * su, sv);
  d.su = r_ * Vec3(-cv * su, cv * cu, 0);
  d.sv = r_ * Vec3(-sv * cu, -sv * su, cv);
  d.suu = r_ * Vec3(-cv * cu, -cv * su, 0);
  d.suv = r_ * Vec3(sv * su, -sv * cu, 0);
  d.svv = r_ * Vec3(-cv * cu, -cv * su, -sv);
  checkFinite(d, uv);
  return d;
}

// --- Torus ---------------------------------------------------------------------------------

TorusSurface::TorusSurface(double majorRadius, double minorRadius, const Vec3& center, const Box2& domain)
    : Surface("torus", domain), R_(majorRadius), r_(minorRadius), c_(center) {
  if (!(std::isfinite(majorRadius) && std::isfinite(minorRadius) && minorRadius > 0.0 && majorRadius > minorRadius &&
        center.allFinite()))
    throw Error(ErrorCode::InvalidArgument, "surface 'torus': need finite radii with major > minor > 0, got " +
                                                fmtParam(majorRadius) + " and " + fmtParam(minorRadius));
  requireOneTurn("torus", "u (around the axis)", domain.lo.x(), domain.hi.x());
  requireOneTurn("torus", "v (around the tube)", domain.lo.y(), domain.hi.y());
}

Vec3 TorusSurface::point(const Vec2& uv) const {
  const double cu = pm::cos(uv.x()), su = pm::sin(uv.x()), cv = pm::cos(uv.y()), sv = pm::sin(uv.y());
  const double w = R_ + r_ * cv;
  return c_ + Vec3(w * cu, w * su, r_ * sv);
}

SurfaceDerivatives TorusSurface::derivatives(const Vec2& uv) const {
  const double cu = pm::cos(uv.x()), su = pm::sin(uv.x()), cv = pm::cos(uv.y()), sv = pm::sin(uv.y());
  const double w = R_ + r_ * cv;
  SurfaceDerivatives d;
  d.p = c_ + Vec3(w * cu, w * su, r_ * sv);
  d.su = Vec3(-w * su, w * cu, 0);
  d.sv = r_ * Vec3(-sv * cu, -sv * su, cv);
  d.suu = Vec3(-w * cu, -w * su, 0);
  d.suv = r_ * Vec3(sv * su, -sv * cu, 0);
  d.svv = r_ * Vec3(-cv * cu, -cv * su, -sv);
  checkFinite(d, uv);
  return d;
}

// --- Bezier --------------------------------------------------------------------------------

namespace {

// Cubic Bernstein polynomials and their first and second derivatives at t.
void bernstein3(double t, double b[4], double db[4], double ddb[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3.0 * t * s * s;
  b[2] = 3.0 * t * t * s;
  b[3] = t * t * t;
  db[0] = -3.0 * s * s;
  db[1] = 3.0 * s * (1.0 - 3.0 * t);
  db[2] = 3.0 * t * (2.0 - 3.0 * t);
  db[3] = 3.0 * t * t;
  ddb[0] = 6.0 * s;
  ddb[1] = 18.0 * t - 12.0;
  ddb[2] = 6.0 - 18.0 * t;
  ddb[3] = 6.0 * t;
}

}  // namespace

BezierPatchSurface::BezierPatchSurface(const std::array<std::array<Vec3, 4>, 4>& controlPoints, std::string name)
    : Surface(std::move(name), Box2{{0.0, 0.0}, {1.0, 1.0}}), cp_(controlPoints) {
  for (const auto& row : cp_)
    for (const auto& p : row)
      if (!(p.allFinite()))
        throw Error(ErrorCode::InvalidSurface, "surface '" + this->name() + "': control point not finite");
}

Vec3 BezierPatchSurface::point(const Vec2& uv) const { return derivatives(uv).p; }

SurfaceDerivatives BezierPatchSurface::derivatives(const Vec2& uv) const {
  double bu[4], dbu[4], ddbu[4], bv[4], dbv[4], ddbv[4];
  bernstein3(uv.x(), bu, dbu, ddbu);
  bernstein3(uv.y(), bv, dbv, ddbv);
  SurfaceDerivatives d;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Vec3& c = cp_[i][j];
      d.p += bu[i] * bv[j] * c;
      d.su += dbu[i] * bv[j] * c;
      d.sv += bu[i] * dbv[j] * c;
      d.suu += ddbu[i] * bv[j] * c;
      d.suv += dbu[i] * dbv[j] * c;
      d.svv += bu[i] * ddbv[j] * c;
    }
  checkFinite(d, uv);
  return d;
}

// --- B-spline ------------------------------------------------------------------------------

namespace {

constexpr int kMaxDegree = 7;

std::vector<double> clampedUniformKnots(int count, int degree) {
  // degree + 1 zeros, count - degree - 1 uniform interior knots, degree + 1 ones.
  std::vector<double> k(count + degree + 1);
  const int spans = count - degree;
  for (int i = 0; i < static_cast<int>(k.size()); ++i) {
    const int j = i - degree;
    k[i] = j <= 0 ? 0.0 : (j >= spans ? 1.0 : static_cast<double>(j) / spans);
  }
  return k;
}

// The degree + 1 nonzero basis functions N_{s-p..s, p}(t) with first and second
// derivatives, where s is the knot span of t. Builds the triangle of lower-degree
// values, then differentiates with N'_{i,j} = j (N_{i,j-1}/(k_{i+j}-k_i) - N_{i+1,j-1}/(k_{i+j+1}-k_{i+1})).
struct BasisEval {
  int span;
  double n[kMaxDegree + 1], dn[kMaxDegree + 1], ddn[kMaxDegree + 1];
};

BasisEval evalBasis(const std::vector<double>& k, int p, int count, double t) {
  BasisEval out{};
  int s = p;
  while (s < count - 1 && t >= k[s + 1]) ++s;  // t = 1 stays in the last span
  out.span = s;
  double tab[kMaxDegree + 1][kMaxDegree + 1] = {};  // tab[j][r] = N_{s-j+r, j}(t)
  tab[0][0] = 1.0;
  auto N = [&](int i, int j) -> double {
    if (j < 0 || i < s - j || i > s) return 0.0;
    return tab[j][i - (s - j)];
  };
  for (int j = 1; j <= p; ++j)
    for (int r = 0; r <= j; ++r) {
      const int i = s - j + r;
      tab[j][r] = safeDiv(t - k[i], k[i + j] - k[i]) * N(i, j - 1) +
                  safeDiv(k[i + j + 1] - t, k[i + j + 1] - k[i + 1]) * N(i + 1, j - 1);
    }
  auto dN = [&](int i, int j) -> double {
    if (j == 0) return 0.0;
    return j * (safeDiv(N(i, j - 1), k[i + j] - k[i]) - safeDiv(N(i + 1, j - 1), k[i + j + 1] - k[i + 1]));
  };
  for (int r = 0; r <= p; ++r) {
    const int i = s - p + r;
    out.n[r] = N(i, p);
    out.dn[r] = dN(i, p);
    out.ddn[r] = p * (safeDiv(dN(i, p - 1), k[i + p] - k[i]) - safeDiv(dN(i + 1, p - 1), k[i + p + 1] - k[i + 1]));
  }
  return out;
}

}  // namespace

BSplinePatchSurface::BSplinePatchSurface(std::vector<std::vector<Vec3>> controlPoints, int degreeU, int degreeV,
                                         std::string name)
    : Surface(std::move(name), Box2{{0.0, 0.0}, {1.0, 1.0}}), cp_(std::move(controlPoints)), p_(degreeU), q_(degreeV) {
  if (!(p_ >= 1 && p_ <= kMaxDegree && q_ >= 1 && q_ <= kMaxDegree))
    throw Error(ErrorCode::InvalidArgument, "surface '" + this->name() + "': degrees must be in [1, 7]");
  const int m = static_cast<int>(cp_.size());
  if (!(m >= p_ + 1))
    throw Error(ErrorCode::InvalidArgument, "surface '" + this->name() +
                                                "': need at least degree + 1 = " + std::to_string(p_ + 1) +
                                                " rows of control points, got " + std::to_string(m));
  const int n = static_cast<int>(cp_[0].size());
  if (!(n >= q_ + 1))
    throw Error(ErrorCode::InvalidArgument, "surface '" + this->name() +
                                                "': need at least degree + 1 = " + std::to_string(q_ + 1) +
                                                " columns of control points, got " + std::to_string(n));
  for (const auto& row : cp_) {
    if (!(static_cast<int>(row.size()) == n))
      throw Error(ErrorCode::InvalidArgument,
                  "surface '" + this->name() + "': control point rows have different lengths");
    for (const auto& p : row)
      if (!(p.allFinite()))
        throw Error(ErrorCode::InvalidSurface, "surface '" + this->name() + "': control point not finite");
  }
  ku_ = clampedUniformKnots(m, p_);
  kv_ = clampedUniformKnots(n, q_);
}

Vec3 BSplinePatchSurface::point(const Vec2& uv) const { return derivatives(uv).p; }

SurfaceDerivatives BSplinePatchSurface::derivatives(const Vec2& uv) const {
  const int m = static_cast<int>(cp_.size()), n = static_cast<int>(cp_[0].size());
  const double u = std::min(std::max(uv.x(), 0.0), 1.0), v = std::min(std::max(uv.y(), 0.0), 1.0);
  const BasisEval bu = evalBasis(ku_, p_, m, u);
  const BasisEval bv = evalBasis(kv_, q_, n, v);
  SurfaceDerivatives d;
  for (int a = 0; a <= p_; ++a)
    for (int b = 0; b <= q_; ++b) {
      const Vec3& c = cp_[bu.span - p_ + a][bv.span - q_ + b];
      d.p += bu.n[a] * bv.n[b] * c;
      d.su += bu.dn[a] * bv.n[b] * c;
      d.sv += bu.n[a] * bv.dn[b] * c;
      d.suu += bu.ddn[a] * bv.n[b] * c;
      d.suv += bu.dn[a] * bv.dn[b] * c;
      d.svv += bu.n[a] * bv.ddn[b] * c;
    }
  checkFinite(d, uv);
  return d;
}

// --- Expression surface -----------------------------------------------------------------

ExpressionSurface::ExpressionSurface(Expression x, Expression y, Expression z, const Box2& domain, std::string name)
    : Surface(std::move(name), domain), f_{std::move(x), std::move(y), std::move(z)} {}

ExpressionSurface::ExpressionSurface(const std::string& x, const std::string& y, const std::string& z,
                                     const Box2& domain, std::string name)
    : ExpressionSurface(Expression::parse(x, ExpressionOptions{"x(u,v)", {}}),
                        Expression::parse(y, ExpressionOptions{"y(u,v)", {}}),
                        Expression::parse(z, ExpressionOptions{"z(u,v)", {}}), domain, std::move(name)) {}

Vec3 ExpressionSurface::point(const Vec2& uv) const {
  Vec3 p;
  for (int c = 0; c < 3; ++c) {
    p[c] = f_[c].value(uv.x(), uv.y());
    if (!(std::isfinite(p[c])))
      throw Error(ErrorCode::InvalidSurface,
                  std::string(1, "xyz"[c]) + "(u,v) = " + f_[c].text() + " is NaN or infinite on " + where(uv));
  }
  return p;
}

SurfaceDerivatives ExpressionSurface::derivatives(const Vec2& uv) const {
  SurfaceDerivatives d;
  for (int c = 0; c < 3; ++c) {
    const Dual2 r = f_[c].evaluate(uv.x(), uv.y());
    if (!(std::isfinite(r.f) && std::isfinite(r.fu) && std::isfinite(r.fv) && std::isfinite(r.fuu) &&
          std::isfinite(r.fuv) && std::isfinite(r.fvv)))
      throw Error(ErrorCode::InvalidSurface, std::string(1, "xyz"[c]) + "(u,v) = " + f_[c].text() +
                                                 " or its derivatives are NaN or infinite on " + where(uv));
    d.p[c] = r.f;
    d.su[c] = r.fu;
    d.sv[c] = r.fv;
    d.suu[c] = r.fuu;
    d.suv[c] = r.fuv;
    d.svv[c] = r.fvv;
  }
  return d;
}

SurfaceDerivatives ExpressionSurface::firstDerivatives(const Vec2& uv) const {
  SurfaceDerivatives d;
  for (int c = 0; c < 3; ++c) {
    const Dual1 r = f_[c].evaluateFirst(uv.x(), uv.y());
    if (!(std::isfinite(r.f) && std::isfinite(r.fu) && std::isfinite(r.fv)))
      throw Error(ErrorCode::InvalidSurface, std::string(1, "xyz"[c]) + "(u,v) = " + f_[c].text() +
                                                 " or its derivatives are NaN or infinite on " + where(uv));
    d.p[c] = r.f;
    d.su[c] = r.fu;
    d.sv[c] = r.fv;
  }
  return d;
}

std::shared_ptr<ExpressionSurface> paperP2(const Box2& domain) {
  return std::make_shared<ExpressionSurface>("u", "v", "1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)", domain, "p2");
}

// --- differential geometry ---------------------------------------------------------------

bool isDegenerate(const SurfaceDerivatives& d) {
  const double area = d.su.cross(d.sv).norm();
  const double scale = 0.5 * (d.su.squaredNorm() + d.sv.squaredNorm());
  return !(area > 1e-10 * scale);  // also true when both are 0 or NaN
}

namespace {

Vec3 normalOrThrow(const SurfaceDerivatives& d, const Surface& s, const Vec2& uv) {
  const Vec3 c = d.su.cross(d.sv);
  if (!(!isDegenerate(d)))
    throw Error(ErrorCode::InvalidSurface,
                "degenerate parameterization (|Su x Sv| = " + fmtParam(c.norm()) + ", no normal) on " + s.where(uv));
  return c.normalized();
}

}  // namespace

Mat2 firstFundamentalForm(const Surface& s, const Vec2& uv) { return s.derivatives(uv).firstFundamentalForm(); }

Vec3 unitNormal(const Surface& s, const Vec2& uv) { return normalOrThrow(s.derivatives(uv), s, uv); }

Mat2 secondFundamentalForm(const Surface& s, const Vec2& uv) { return curvature(s, uv).second; }

SurfaceCurvature curvature(const Surface& s, const Vec2& uv) { return curvature(s.derivatives(uv), s, uv); }

SurfaceCurvature curvature(const SurfaceDerivatives& d, const Surface& s, const Vec2& uv) {
  SurfaceCurvature c;
  c.normal = normalOrThrow(d, s, uv);
  const Mat2 g = d.firstFundamentalForm();
  Mat2 h;
  h(0, 0) = d.suu.dot(c.normal);
  h(0, 1) = h(1, 0) = d.suv.dot(c.normal);
  h(1, 1) = d.svv.dot(c.normal);
  c.first = g;
  c.second = h;
  // Generalized symmetric eigenproblem II x = k G x, reduced with the Cholesky factor
  // G = L L^T to the symmetric A = L^-1 II L^-T: its closed-form eigen-decomposition keeps
  // k accurate near umbilics (H^2 - K would cancel), and x = L^-T y comes out G-orthonormal.
  const double l11 = std::sqrt(g(0, 0)), l21 = g(0, 1) / l11, l22 = std::sqrt(g.determinant() / g(0, 0));
  Mat2 linv;  // L^-1
  linv << 1.0 / l11, 0.0, -l21 / (l11 * l22), 1.0 / l22;
  const Mat2 a = linv * h * linv.transpose();
  const double mid = 0.5 * (a(0, 0) + a(1, 1));
  const double rad = pm::hypot(0.5 * (a(0, 0) - a(1, 1)), 0.5 * (a(0, 1) + a(1, 0)));
  c.k1 = mid + rad;
  c.k2 = mid - rad;
  c.gaussian = c.k1 * c.k2;
  c.mean = mid;
  // Eigenvector angle of A for k1; at an umbilic atan2(0, 0) = 0 picks the Su direction.
  const double theta = 0.5 * pm::atan2(a(0, 1) + a(1, 0), a(0, 0) - a(1, 1));
  const Vec2 y1(pm::cos(theta), pm::sin(theta)), y2(-pm::sin(theta), pm::cos(theta));
  // det[x y] = det(L^-T) > 0, so dir1 x dir2 = +n.
  const Vec2 x = linv.transpose() * y1, y = linv.transpose() * y2;
  c.uvDir1 = x;
  c.uvDir2 = y;
  c.dir1 = x.x() * d.su + x.y() * d.sv;
  c.dir2 = y.x() * d.su + y.y() * d.sv;
  return c;
}

}  // namespace anisomesh

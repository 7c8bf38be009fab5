#include "anisomesh/geometry/curve.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/geometry/quadrature.h"

namespace anisomesh {

// The piece i of a curve with cumulative normalized lengths cum (cum[0] = 0, cum.back() = 1)
// holding t (clamped to [0, 1]), and t's position in it in [0, 1].
static int pieceAt(const std::vector<double>& cum, double t, double* local) {
  t = std::min(std::max(t, 0.0), 1.0);
  const auto it = std::upper_bound(cum.begin(), cum.end(), t);
  int i = static_cast<int>(it - cum.begin()) - 1;
  i = std::min(std::max(i, 0), static_cast<int>(cum.size()) - 2);
  const double w = cum[i + 1] - cum[i];
  *local = w > 0 ? (t - cum[i]) / w : 0.0;
  return i;
}
namespace {
// Not M_PI: strict C++17 headers (libc++/musl under Emscripten) need not define it.
constexpr double kPiValue = 3.14159265358979323846;
}  // namespace

std::string formatPoint(const Vec2& p) {
  std::ostringstream os;
  os.precision(10);
  os << "(" << p.x() << ", " << p.y() << ")";
  return os.str();
}

double Curve::length() const { return curveLength(*this, 0.0, 1.0); }

double curveLength(const Curve& c, double a, double b) {
  return integrateAdaptive([&c](double t) { return c.derivative(t).norm(); }, a, b, 1e-10);
}

LineCurve::LineCurve(const Vec2& p1, const Vec2& p2, int ref) : p1_(p1), p2_(p2) {
  require(p1.allFinite() && p2.allFinite(), ErrorCode::InvalidArgument, "line end points must be finite");
  setRef(ref);
}

ArcCurve::ArcCurve(const Vec2& center, double radius, double startAngle, double endAngle, int ref)
    : center_(center), radius_(radius), a0_(startAngle), a1_(endAngle) {
  require(center.allFinite(), ErrorCode::InvalidArgument, "arc center must be finite");
  require(std::isfinite(radius) && radius > 0.0, ErrorCode::InvalidArgument,
          "arc radius must be finite and positive, got " + std::to_string(radius));
  require(std::isfinite(startAngle) && std::isfinite(endAngle), ErrorCode::InvalidArgument,
          "arc angles must be finite");
  setRef(ref);
}

ArcCurve ArcCurve::throughPoints(const Vec2& a, const Vec2& b, const Vec2& c, int ref) {
  // Circumcenter from the perpendicular bisectors.
  const Vec2 ab = b - a, ac = c - a;
  const double d = 2.0 * (ab.x() * ac.y() - ab.y() * ac.x());
  const double scale = std::max(ab.squaredNorm(), ac.squaredNorm());
  require(std::abs(d) > 1e-12 * scale && scale > 0.0, ErrorCode::InvalidArgument,
          "arc through " + formatPoint(a) + ", " + formatPoint(b) + ", " + formatPoint(c) +
              ": points are collinear or coincide");
  const Vec2 off((ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm()) / d,
                 (ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm()) / d);
  const Vec2 center = a + off;
  const double r = off.norm();
  auto ang = [&](const Vec2& p) { return pm::atan2(p.y() - center.y(), p.x() - center.x()); };
  const double a0 = ang(a);
  // Sweep from a to c counter-clockwise when b lies left of a->c turn order (d > 0).
  double sweepB = ang(b) - a0, sweepC = ang(c) - a0;
  if (d > 0) {
    while (sweepB <= 0) sweepB += 2 * kPiValue;
    while (sweepC <= 0) sweepC += 2 * kPiValue;
  } else {
    while (sweepB >= 0) sweepB -= 2 * kPiValue;
    while (sweepC >= 0) sweepC -= 2 * kPiValue;
  }
  return ArcCurve(center, r, a0, a0 + sweepC, ref);
}

ArcCurve ArcCurve::circle(const Vec2& center, double radius, int ref) {
  return ArcCurve(center, radius, 0.0, 2.0 * kPiValue, ref);
}

Vec2 ArcCurve::point(double t) const {
  const double a = a0_ + t * (a1_ - a0_);
  return center_ + radius_ * Vec2(pm::cos(a), pm::sin(a));
}

Vec2 ArcCurve::derivative(double t) const {
  const double a = a0_ + t * (a1_ - a0_), w = a1_ - a0_;
  return radius_ * w * Vec2(-pm::sin(a), pm::cos(a));
}

void ArcCurve::pointAndDerivative(double t, Vec2& p, Vec2& d) const {
  const double a = a0_ + t * (a1_ - a0_), w = a1_ - a0_;
  double s, c;
  pm::sincos(a, s, c);  // the bits of pm::sin(a), pm::cos(a)
  p = center_ + radius_ * Vec2(c, s);
  d = radius_ * w * Vec2(-s, c);
}

Vec2 ArcCurve::secondDerivative(double t) const {
  const double a = a0_ + t * (a1_ - a0_), w = a1_ - a0_;
  return -radius_ * w * w * Vec2(pm::cos(a), pm::sin(a));
}

double ArcCurve::length() const { return radius_ * std::abs(a1_ - a0_); }

PolylineCurve::PolylineCurve(std::vector<Vec2> points, int ref, bool keepVertices)
    : pts_(std::move(points)), keepVertices_(keepVertices) {
  require(pts_.size() >= 2, ErrorCode::InvalidArgument, "a polyline needs at least 2 points");
  cum_.assign(pts_.size(), 0.0);
  for (size_t i = 1; i < pts_.size(); ++i) {
    require(pts_[i].allFinite(), ErrorCode::InvalidArgument, "polyline points must be finite");
    cum_[i] = cum_[i - 1] + (pts_[i] - pts_[i - 1]).norm();
  }
  total_ = cum_.back();
  // A zero-length polyline keeps a uniform parameterization; validation reports it.
  for (size_t i = 0; i < cum_.size(); ++i)
    cum_[i] = total_ > 0 ? cum_[i] / total_ : double(i) / double(cum_.size() - 1);
  cum_.back() = 1.0;
  setRef(ref);
}

int PolylineCurve::segmentAt(double t, double* local) const { return pieceAt(cum_, t, local); }

Vec2 PolylineCurve::point(double t) const {
  double u;
  const int i = segmentAt(t, &u);
  return pts_[i] + u * (pts_[i + 1] - pts_[i]);
}

Vec2 PolylineCurve::derivative(double t) const {
  double u;
  const int i = segmentAt(t, &u);
  const double w = cum_[i + 1] - cum_[i];
  return w > 0 ? Vec2((pts_[i + 1] - pts_[i]) / w) : Vec2(Vec2::Zero());
}

std::vector<double> PolylineCurve::breakpoints() const {
  if (!keepVertices_) return {};
  return std::vector<double>(cum_.begin() + 1, cum_.end() - 1);
}

namespace {

// The derivative at b of the parabola through a, b, c at parameters -da, 0, dc (a one-sided
// difference when a neighbour coincides).
Vec2 besselTangent(const Vec2& a, const Vec2& b, const Vec2& c, double da, double dc) {
  if (!(da > 0)) return dc > 0 ? Vec2((c - b) / dc) : Vec2(Vec2::Zero());
  if (!(dc > 0)) return (b - a) / da;
  return (dc / (da + dc)) * (b - a) / da + (da / (da + dc)) * (c - b) / dc;
}

// The derivative at a of the parabola through a, b, c at parameters 0, dab, dab + dbc.
Vec2 endTangent(const Vec2& a, const Vec2& b, const Vec2& c, double dab, double dbc) {
  if (!(dab > 0)) return Vec2::Zero();
  if (!(dbc > 0)) return (b - a) / dab;
  return ((2 * dab + dbc) / (dab + dbc)) * (b - a) / dab - (dab / (dab + dbc)) * (c - b) / dbc;
}

}  // namespace

SplineCurve::SplineCurve(std::vector<Vec2> points, int ref, const Vec2* before, const Vec2* after)
    : pts_(std::move(points)) {
  require(pts_.size() >= 2, ErrorCode::InvalidArgument, "a spline needs at least 2 points");
  for (const Vec2& p : pts_) require(p.allFinite(), ErrorCode::InvalidArgument, "spline points must be finite");
  const size_t n = pts_.size();
  cum_.assign(n, 0.0);
  for (size_t i = 1; i < n; ++i) cum_[i] = cum_[i - 1] + (pts_[i] - pts_[i - 1]).norm();
  const double total = cum_.back();
  for (size_t i = 0; i < n; ++i) cum_[i] = total > 0 ? cum_[i] / total : double(i) / double(n - 1);
  cum_.back() = 1.0;
  const double scale = total > 0 ? total : 1.0;  // neighbours beyond the ends, in parameter units
  tangents_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (i > 0 && i + 1 < n) {
      tangents_[i] = besselTangent(pts_[i - 1], pts_[i], pts_[i + 1], cum_[i] - cum_[i - 1], cum_[i + 1] - cum_[i]);
    } else if (i == 0 && before) {
      tangents_[i] = besselTangent(*before, pts_[0], pts_[1], (pts_[0] - *before).norm() / scale, cum_[1]);
    } else if (i + 1 == n && after) {
      tangents_[i] = besselTangent(pts_[n - 2], pts_[n - 1], *after, cum_[n - 1] - cum_[n - 2],
                                   (*after - pts_[n - 1]).norm() / scale);
    } else if (n == 2) {
      tangents_[i] = pts_[1] - pts_[0];  // a straight piece
    } else if (i == 0) {
      tangents_[i] = endTangent(pts_[0], pts_[1], pts_[2], cum_[1], cum_[2] - cum_[1]);
    } else {
      tangents_[i] =
          -endTangent(pts_[n - 1], pts_[n - 2], pts_[n - 3], cum_[n - 1] - cum_[n - 2], cum_[n - 2] - cum_[n - 3]);
    }
  }
  setRef(ref);
}

int SplineCurve::segmentAt(double t, double* local) const { return pieceAt(cum_, t, local); }

Vec2 SplineCurve::point(double t) const {
  double u;
  const int i = segmentAt(t, &u);
  const double w = cum_[i + 1] - cum_[i];
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * pts_[i] + (u3 - 2 * u2 + u) * w * tangents_[i] + (-2 * u3 + 3 * u2) * pts_[i + 1] +
         (u3 - u2) * w * tangents_[i + 1];
}

Vec2 SplineCurve::derivative(double t) const {
  double u;
  const int i = segmentAt(t, &u);
  const double w = cum_[i + 1] - cum_[i];
  if (!(w > 0)) return tangents_[i];
  const double u2 = u * u;
  return ((6 * u2 - 6 * u) * (pts_[i] - pts_[i + 1])) / w + (3 * u2 - 4 * u + 1) * tangents_[i] +
         (3 * u2 - 2 * u) * tangents_[i + 1];
}

Vec2 SplineCurve::secondDerivative(double t) const {
  double u;
  const int i = segmentAt(t, &u);
  const double w = cum_[i + 1] - cum_[i];
  if (!(w > 0)) return Vec2::Zero();
  return ((12 * u - 6) * (pts_[i] - pts_[i + 1])) / (w * w) +
         ((6 * u - 4) * tangents_[i] + (6 * u - 2) * tangents_[i + 1]) / w;
}

BezierCurve::BezierCurve(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, int ref) : p_{p0, p1, p2, p3} {
  for (const Vec2& p : p_) require(p.allFinite(), ErrorCode::InvalidArgument, "Bezier control points must be finite");
  setRef(ref);
}

Vec2 BezierCurve::point(double t) const {
  const double s = 1.0 - t;
  return s * s * s * p_[0] + 3 * s * s * t * p_[1] + 3 * s * t * t * p_[2] + t * t * t * p_[3];
}

Vec2 BezierCurve::derivative(double t) const {
  const double s = 1.0 - t;
  return 3 * (s * s * (p_[1] - p_[0]) + 2 * s * t * (p_[2] - p_[1]) + t * t * (p_[3] - p_[2]));
}

Vec2 BezierCurve::secondDerivative(double t) const {
  return 6 * ((1.0 - t) * (p_[2] - 2 * p_[1] + p_[0]) + t * (p_[3] - 2 * p_[2] + p_[1]));
}

BSplineCurve::BSplineCurve(std::vector<Vec2> controlPoints, int ref) : ctrl_(std::move(controlPoints)) {
  const int n = static_cast<int>(ctrl_.size());
  require(n >= 4, ErrorCode::InvalidArgument,
          "a cubic B-spline needs at least 4 control points, got " + std::to_string(n));
  for (const Vec2& p : ctrl_)
    require(p.allFinite(), ErrorCode::InvalidArgument, "B-spline control points must be finite");
  // Clamped uniform knots: 4 zeros, n - 4 uniform interior knots, 4 ones.
  const int spans = n - 3;
  knots_.assign(4, 0.0);
  for (int i = 1; i < spans; ++i) knots_.push_back(double(i) / spans);
  knots_.insert(knots_.end(), 4, 1.0);
  // Derivative splines: Q_i = p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1}) on the knots without the ends.
  auto derive = [](int p, const std::vector<double>& k, const std::vector<Vec2>& c, std::vector<double>* kOut) {
    std::vector<Vec2> q;
    for (size_t i = 0; i + 1 < c.size(); ++i) {
      const double den = k[i + p + 1] - k[i + 1];
      q.push_back(den > 0 ? Vec2(p * (c[i + 1] - c[i]) / den) : Vec2(Vec2::Zero()));
    }
    kOut->assign(k.begin() + 1, k.end() - 1);
    return q;
  };
  d1_ = derive(3, knots_, ctrl_, &knots1_);
  d2_ = derive(2, knots1_, d1_, &knots2_);
  setRef(ref);
}

Vec2 BSplineCurve::evaluate(int p, const std::vector<double>& k, const std::vector<Vec2>& c, double t) {
  t = std::min(std::max(t, 0.0), 1.0);
  const int n = static_cast<int>(c.size());
  // Knot span s with k[s] <= t < k[s + 1], p <= s <= n - 1.
  int s = static_cast<int>(std::upper_bound(k.begin(), k.end(), t) - k.begin()) - 1;
  s = std::min(std::max(s, p), n - 1);
  std::vector<Vec2> d(c.begin() + (s - p), c.begin() + (s + 1));
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const int i = j + s - p;
      const double den = k[i + p - r + 1] - k[i];
      const double a = den > 0 ? (t - k[i]) / den : 0.0;
      d[j] = (1.0 - a) * d[j - 1] + a * d[j];
    }
  return d[p];
}

Vec2 BSplineCurve::point(double t) const { return evaluate(3, knots_, ctrl_, t); }
Vec2 BSplineCurve::derivative(double t) const { return evaluate(2, knots1_, d1_, t); }
Vec2 BSplineCurve::secondDerivative(double t) const { return evaluate(1, knots2_, d2_, t); }

}  // namespace anisomesh

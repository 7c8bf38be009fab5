#include "anisomesh/geometry/surface_metric.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "anisomesh/core/error.h"

namespace anisomesh {

namespace {

std::string fmtBound(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

Mat2 symmetrized(const Mat2& m) {
  Mat2 s = m;
  s(0, 1) = s(1, 0) = 0.5 * (m(0, 1) + m(1, 0));
  return s;
}

// Metric from a tensor symmetric by construction: a cheap SPD check on the hot path,
// Metric::fromTensor (with its detailed InvalidMetric message) only when it fails.
Metric metricFromSymmetric(const Mat2& m) {
  const Mat2 mt = sqrtSpd(m);
  if (m.allFinite() && m(0, 0) > 0.0 && m.determinant() > 0.0 && mt.allFinite())
    return Metric::fromTransformUnchecked(mt);
  return Metric::fromTensor(m);
}

// Sizes along the two principal directions with the d_max cap applied.
void cappedSizes(const SurfaceCurvature& c, const SurfaceMetricOptions& o, double& h1, double& h2) {
  h1 = curvatureSize(c.k1, o);
  h2 = curvatureSize(c.k2, o);
  if (h1 > o.maxAspectRatio * h2) h1 = o.maxAspectRatio * h2;
  if (h2 > o.maxAspectRatio * h1) h2 = o.maxAspectRatio * h1;
}

// J^T M3 J restricted to the principal frame: sum_i (G d_i)(G d_i)^T / h_i^2, since J d_i = e_i.
Metric curvatureParameterMetric(const SurfaceCurvature& c, const SurfaceMetricOptions& o) {
  double h1, h2;
  cappedSizes(c, o, h1, h2);
  const Vec2 a1 = c.first * c.uvDir1, a2 = c.first * c.uvDir2;
  const Mat2 m = a1 * a1.transpose() / (h1 * h1) + a2 * a2.transpose() / (h2 * h2);
  return metricFromSymmetric(symmetrized(m));
}

}  // namespace

void validate(const SurfaceMetricOptions& o) {
  if (!(std::isfinite(o.chordTolerance) && std::isfinite(o.angleTolerance) && o.chordTolerance >= 0.0 &&
        o.angleTolerance >= 0.0))
    throw Error(ErrorCode::InvalidArgument,
                "surface metric: chordTolerance and angleTolerance must be finite and >= 0 "
                "(0: off), got " +
                    fmtBound(o.chordTolerance) + " and " + fmtBound(o.angleTolerance));
  if (!(std::isfinite(o.hmin) && o.hmin > 0.0 && std::isfinite(o.hmax) && o.hmax >= o.hmin))
    throw Error(ErrorCode::InvalidArgument, "surface metric: need 0 < hmin <= hmax, got hmin = " + fmtBound(o.hmin) +
                                                ", hmax = " + fmtBound(o.hmax));
  if (!(std::isfinite(o.maxAspectRatio) && o.maxAspectRatio >= 1.0))
    throw Error(ErrorCode::InvalidArgument,
                "surface metric: maxAspectRatio must be >= 1, got " + fmtBound(o.maxAspectRatio));
}

double curvatureSize(double k, const SurfaceMetricOptions& o) {
  const double ak = std::abs(k);
  double h = o.hmax;
  if (ak > 0.0) {
    if (o.chordTolerance > 0.0) h = std::min(h, std::sqrt(8.0 * o.chordTolerance / ak));
    if (o.angleTolerance > 0.0) h = std::min(h, o.angleTolerance / ak);
  }
  return std::min(std::max(h, o.hmin), o.hmax);
}

Mat3 TangentMetric::tensor() const {
  return dir1 * dir1.transpose() / (h1 * h1) + dir2 * dir2.transpose() / (h2 * h2) +
         normal * normal.transpose() / (hn * hn);
}

Mat3 TangentMetric::transform() const {
  return dir1 * dir1.transpose() / h1 + dir2 * dir2.transpose() / h2 + normal * normal.transpose() / hn;
}

TangentMetric requestedMetric3D(const Surface& s, const Vec2& uv, const SurfaceMetricOptions& options) {
  validate(options);
  const SurfaceCurvature c = curvature(s, uv);
  TangentMetric t;
  cappedSizes(c, options, t.h1, t.h2);
  t.hn = std::min(t.h1, t.h2);
  t.dir1 = c.dir1.normalized();
  t.dir2 = c.dir2.normalized();
  t.normal = c.normal;
  return t;
}

Metric pullBackMetric(const Mat3& m3, const SurfaceDerivatives& d) {
  const Eigen::Matrix<double, 3, 2> j = d.jacobian();
  return metricFromSymmetric(symmetrized(j.transpose() * m3 * j));
}

Metric pullBackTangentMetric(const Metric& m, const Vec3& t1, const Vec3& t2, const SurfaceDerivatives& d) {
  Eigen::Matrix<double, 2, 3> bt;  // B^T
  bt.row(0) = t1.transpose();
  bt.row(1) = t2.transpose();
  const Mat2 a = bt * d.jacobian();  // B^T J: tangent-basis coordinates of Su, Sv
  return metricFromSymmetric(symmetrized(a.transpose() * m.tensor() * a));
}

Metric parameterMetric(const Surface& s, const Vec2& uv, const SurfaceMetricOptions& options) {
  validate(options);
  return curvatureParameterMetric(curvature(s, uv), options);
}

Mat2 parameterizationMatrix(const Surface& s, const Vec2& uv) {
  Mat2 mp = sqrtSpd(s.derivatives(uv).firstFundamentalForm());
  if (!(mp.allFinite())) throw Error(ErrorCode::InvalidSurface, "parameterization matrix not finite on " + s.where(uv));
  return mp;
}

// --- control space ------------------------------------------------------------------------

SurfaceCurvatureControlSpace::SurfaceCurvatureControlSpace(std::shared_ptr<const Surface> surface,
                                                           const SurfaceMetricOptions& options)
    : surface_(std::move(surface)), options_(options) {
  if (!(surface_ != nullptr)) throw Error(ErrorCode::InvalidArgument, "surface control space: no surface");
  validate(options_);
}

Vec2 SurfaceCurvatureControlSpace::clampToDomain(const Vec2& p) const {
  const Box2& b = surface_->domain();
  return p.cwiseMax(b.lo).cwiseMin(b.hi);
}

Metric SurfaceCurvatureControlSpace::metricAt(const Vec2& p) const {
  const Vec2 q = clampToDomain(p);
  const SurfaceDerivatives d = surface_->derivatives(q);
  Metric m = curvatureParameterMetric(curvature(d, *surface_, q), options_);
  if (user2d_) m = intersect(m, user2d_(q));
  if (user3d_) m = intersect(m, pullBackMetric(user3d_(d.p), d));
  return m;
}

std::optional<Metric> SurfaceCurvatureControlSpace::tryMetricAt(const Vec2& p) const {
  try {
    return metricAt(p);
  } catch (const Error& e) {
    if (e.code() == ErrorCode::InvalidSurface) return std::nullopt;
    throw;
  }
}

Mat2 SurfaceCurvatureControlSpace::parameterizationAt(const Vec2& p) const {
  return parameterizationMatrix(*surface_, clampToDomain(p));
}

// --- 3D measures ----------------------------------------------------------------------------

double edgeLength3D(const Vec3& p, const Vec3& q, const Mat3& m3) {
  const Vec3 e = q - p;
  return std::sqrt(std::max(e.dot(m3 * e), 0.0));
}

double edgeLength3D(const Surface& s, const Vec2& a, const Vec2& b, const SurfaceMetricOptions& options) {
  const Vec3 chord = s.point(b) - s.point(a);
  const double la = (requestedMetric3D(s, a, options).transform() * chord).norm();
  const double lm = (requestedMetric3D(s, 0.5 * (a + b), options).transform() * chord).norm();
  const double lb = (requestedMetric3D(s, b, options).transform() * chord).norm();
  return (la + 4.0 * lm + lb) / 6.0;
}

double triangleQuality3D(const Vec3& a, const Vec3& b, const Vec3& c, const Mat3& m3) {
  // Metric lengths and area from the metric Gram matrix of two edges: no square root of M3 needed.
  const Vec3 e1 = b - a, e2 = c - a, e3 = c - b;
  const double g11 = e1.dot(m3 * e1), g22 = e2.dot(m3 * e2), g12 = e1.dot(m3 * e2);
  const double area = 0.5 * std::sqrt(std::max(g11 * g22 - g12 * g12, 0.0));
  const double sum = g11 + g22 + e3.dot(m3 * e3);
  return sum > 0.0 ? 4.0 * std::sqrt(3.0) * area / sum : 0.0;
}

double triangleQuality3D(const Surface& s, const Vec2& a, const Vec2& b, const Vec2& c,
                         const SurfaceMetricOptions& options) {
  const Mat3 m3 = requestedMetric3D(s, (a + b + c) / 3.0, options).tensor();
  return triangleQuality3D(s.point(a), s.point(b), s.point(c), m3);
}

double chordDeviation(const Surface& s, const Vec2& a, const Vec2& b, const ChordDeviationOptions& options) {
  if (!(options.samples >= 1)) throw Error(ErrorCode::InvalidArgument, "chord deviation: samples must be >= 1");
  const Vec3 pa = s.point(a), pb = s.point(b), e = pb - pa;
  const double ee = e.squaredNorm();
  double worst = 0.0;
  for (int i = 1; i <= options.samples; ++i) {
    const double t = static_cast<double>(i) / (options.samples + 1);
    worst = std::max(worst, chordGap(s.point((1.0 - t) * a + t * b), pa, e, ee));
  }
  return worst;
}

}  // namespace anisomesh

#include "anisomesh/metric/metric.h"
#include "anisomesh/core/number_text.h"

#include <cmath>
#include <sstream>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/metric/sym_eigen.h"

namespace anisomesh {
namespace {

std::string describe(const Mat2& m) {
  std::ostringstream os;
  os << "[" << m(0, 0) << ", " << m(0, 1) << "; " << m(1, 0) << ", " << m(1, 1) << "]";
  return os.str();
}

// A sufficient condition for the checks of checkSpd, cheaper than its eigenvalues (a
// metric read from a file per vertex): symmetric, diagonal in [1e-100, 1e100], |m12| <=
// 1e100 (no overflow or underflow below) and det > 1e-10 tr^2 (computed). Then the
// smallest eigenvalue is l2 >= det / tr > 0.99e-10 tr, far above the rounding error of
// symEigenValues' mean - hypot (a few ulps of tr), so its l2 is positive as well.
bool clearlySpd(const Mat2& m) {
  const double a = m(0, 0), b = m(0, 1), c = m(1, 1);
  if (!(b == m(1, 0) && a >= 1e-100 && a <= 1e100 && c >= 1e-100 && c <= 1e100 && std::abs(b) <= 1e100)) return false;
  const double t = a + c;
  return a * c - b * b > 1e-10 * (t * t);
}

// Checks build their messages only on failure: they sit on the hot path of every
// validated metric construction.
void checkSpd(const Mat2& m, const char* what) {
  if (clearlySpd(m)) return;
  if (!m.allFinite())
    throw Error(ErrorCode::InvalidMetric, std::string(what) + " has a NaN or infinite entry: " + describe(m));
  const double scale = m.cwiseAbs().maxCoeff();
  if (!(std::abs(m(0, 1) - m(1, 0)) <= 1e-12 * scale))
    throw Error(ErrorCode::InvalidMetric, std::string(what) + " is not symmetric: " + describe(m));
  const SymEigen2 e = symEigenValues(m);
  if (!(e.l2 > 0.0 && std::isfinite(1.0 / std::sqrt(e.l2))))
    throw Error(ErrorCode::InvalidMetric, std::string(what) + " is not positive definite: " + describe(m));
}

// Sizes whose tensor 1 / h^2 (and its products in intersections) stays finite and normal:
// 1e-300 overflowed to an infinite tensor and failed far from here ("alpha must be finite").
constexpr double kSmallestSize = 1e-100, kLargestSize = 1e100;

void checkSize(double h, const char* name) {
  if (!(std::isfinite(h) && h > 0.0))
    throw Error(ErrorCode::InvalidMetric,
                std::string("metric size ") + name + " must be finite and positive, got " + numberText(h));
  if (!(h >= kSmallestSize && h <= kLargestSize))
    throw Error(ErrorCode::InvalidMetric,
                std::string("metric size ") + name + " = " + numberText(h) + " is outside [1e-100, 1e100]");
}

}  // namespace

Mat2 sqrtSpd(const Mat2& m) {
  // For SPD 2x2: sqrt(M) = (M + sqrt(det M) I) / sqrt(tr M + 2 sqrt(det M)).
  const double s = std::sqrt(std::max(m.determinant(), 0.0));
  const double t = std::sqrt(m.trace() + 2.0 * s);
  Mat2 r = (m + s * Mat2::Identity()) / t;
  r(0, 1) = r(1, 0) = 0.5 * (r(0, 1) + r(1, 0));
  return r;
}

Metric Metric::fromSizes(double alpha, double h1, double h2) {
  require(std::isfinite(alpha), ErrorCode::InvalidMetric, "metric direction alpha must be finite");
  checkSize(h1, "h1");
  checkSize(h2, "h2");
  return Metric(fromEigen(1.0 / h1, 1.0 / h2, alpha));
}

Metric Metric::isotropic(double h) {
  checkSize(h, "h");
  return Metric(Mat2::Identity() / h);
}

Metric Metric::fromTensor(const Mat2& m) {
  checkSpd(m, "metric tensor");
  Mat2 sym = m;
  sym(0, 1) = sym(1, 0) = 0.5 * (m(0, 1) + m(1, 0));
  return Metric(sqrtSpd(sym));
}

Metric Metric::fromTensor(double m11, double m12, double m22) {
  Mat2 m;
  m << m11, m12, m12, m22;
  return fromTensor(m);
}

Metric Metric::fromTransform(const Mat2& mt) {
  checkSpd(mt, "metric transformation matrix");
  Mat2 sym = mt;
  sym(0, 1) = sym(1, 0) = 0.5 * (mt(0, 1) + mt(1, 0));
  return Metric(sym);
}

MetricSizes Metric::sizes() const {
  const SymEigen2 e = symEigen(mt_);
  // The larger eigenvalue of Mt is the inverse of the smaller requested size.
  double alpha = e.theta;
  if (alpha <= -M_PI / 2) alpha += M_PI;
  if (alpha > M_PI / 2) alpha -= M_PI;
  return {alpha, 1.0 / e.l1, 1.0 / e.l2};
}

double Metric::smallestSize() const { return 1.0 / symEigenValues(mt_).l1; }

double Metric::aspectRatio() const {
  const SymEigen2 e = symEigenValues(mt_);
  return e.l1 / e.l2;
}

Metric intersect(const Metric& a, const Metric& b) {
  // N = Mt_a^-1 M_b Mt_a^-1 is symmetric; its eigenvectors give the common basis.
  const Mat2 ia = a.transform().inverse();
  const Mat2 n = ia * b.tensor() * ia;
  const SymEigen2 e = symEigenValues(n);
  if (e.l2 >= 1.0) return b;  // b is at least as fine in every direction
  if (e.l1 <= 1.0) return a;  // a is at least as fine in every direction
  // Here l2 < 1 < l1: Q = I + (l1 - 1) v1 v1^T, and v1 v1^T = (N - l2 I) / (l1 - l2).
  const double w = (e.l1 - 1.0) / (e.l1 - e.l2);
  Mat2 q = w * n;
  q(0, 0) += 1.0 - w * e.l2;
  q(1, 1) += 1.0 - w * e.l2;
  q(0, 1) = q(1, 0) = 0.5 * (q(0, 1) + q(1, 0));
  const Mat2 m = a.transform() * q * a.transform();
  return Metric::fromTransformUnchecked(sqrtSpd(m));
}

bool metricInside(const Metric& a, const Metric& b) {
  // Same test as intersect(b, a)'s first branch.
  const Mat2 ib = b.transform().inverse();
  return symEigenValues(ib * a.tensor() * ib).l2 >= 1.0;
}

Metric interpolate(const Metric& a, const Metric& b, double t) {
  return Metric::fromTransformUnchecked((1.0 - t) * a.transform() + t * b.transform());
}

Metric weightedAverage(const Metric* metrics, const double* weights, int n) {
  Mat2 sum = Mat2::Zero();
  double wsum = 0.0;
  for (int i = 0; i < n; ++i) {
    sum += weights[i] * metrics[i].transform();
    wsum += weights[i];
  }
  require(wsum > 0.0, ErrorCode::InvalidArgument, "weighted average of metrics needs a positive total weight");
  return Metric::fromTransformUnchecked(sum / wsum);
}

double difference(const Metric& a, const Metric& b) {
  const Mat2 ia = a.transform().inverse();
  const SymEigen2 e = symEigenValues(ia * b.tensor() * ia);
  return std::max(std::sqrt(e.l1), 1.0 / std::sqrt(e.l2)) - 1.0;
}

}  // namespace anisomesh

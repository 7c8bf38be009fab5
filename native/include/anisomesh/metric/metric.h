#pragma once
// The metric of the paper (section 2, eqs. 1-2): a 2x2 symmetric positive-definite
// tensor M, stored as its transformation matrix Mt (the symmetric square root,
// M = Mt Mt^T) because interpolation, minimum and comparison act on Mt.
#include "anisomesh/core/types.h"

namespace anisomesh {

// (alpha, h1, h2): requested edge length h1 along the unit direction at angle alpha
// and h2 along its normal.
struct MetricSizes {
  double alpha = 0.0;
  double h1 = 1.0;
  double h2 = 1.0;
};

class Metric {
 public:
  // The identity metric: unit size in every direction.
  Metric() : mt_(Mat2::Identity()) {}

  // M = R(alpha) diag(1/h1^2, 1/h2^2) R(alpha)^T; throws InvalidMetric on NaN, infinite, zero or negative sizes.
  static Metric fromSizes(double alpha, double h1, double h2);
  // Isotropic metric of size h; throws InvalidMetric unless h is finite and positive.
  static Metric isotropic(double h);
  // From the tensor M; throws InvalidMetric unless M is finite, symmetric and positive definite.
  static Metric fromTensor(const Mat2& m);
  // From the components m11, m12, m22 of M (the Medit .sol order); validated like fromTensor.
  static Metric fromTensor(double m11, double m12, double m22);
  // From the transformation matrix Mt; validated like fromTensor.
  static Metric fromTransform(const Mat2& mt);
  // From a transformation matrix known to be symmetric positive definite (interpolation results).
  static Metric fromTransformUnchecked(const Mat2& mt) { return Metric(mt); }

  // Mt, with M = Mt Mt^T and P' = Mt P (eq. 1).
  const Mat2& transform() const { return mt_; }
  // The tensor M = Mt Mt^T.
  Mat2 tensor() const { return mt_ * mt_; }
  // Image of a vector (or point) in metric space: Mt v.
  Vec2 apply(const Vec2& v) const { return mt_ * v; }
  // Metric length of a vector: sqrt(v^T M v) = |Mt v|.
  double length(const Vec2& v) const { return (mt_ * v).norm(); }
  // Requested edge length in the direction of dir (dir need not be unit, must be nonzero).
  double sizeAlong(const Vec2& dir) const { return dir.norm() / length(dir); }
  // Decomposition into (alpha, h1, h2) with h1 <= h2 and alpha in (-pi/2, pi/2].
  MetricSizes sizes() const;
  // sizes().h1 (the smallest requested size) without computing the direction.
  double smallestSize() const;
  // Ratio of the larger to the smaller requested size (>= 1).
  double aspectRatio() const;
  // The metric whose requested sizes are s times this one's (tensor M / s^2): "sM" of eqs. 8-9.
  Metric scaled(double s) const { return Metric(mt_ / s); }
  // Area of the unit ball in physical space relative to the unit disc: h1 * h2.
  double sizeProduct() const { return 1.0 / mt_.determinant(); }

 private:
  explicit Metric(const Mat2& mt) : mt_(mt) {}
  Mat2 mt_;
};

// Symmetric square root of a symmetric positive-definite 2x2 matrix (closed form).
Mat2 sqrtSpd(const Mat2& m);

// Metric intersection, the paper's min(M1, M2): the largest unit ball inside both,
// by simultaneous reduction (per common eigenvector, the larger metric value).
Metric intersect(const Metric& a, const Metric& b);

// True when a's unit ball lies inside b's (a requests sizes <= b's in every direction):
// exactly when intersect(b, a) returns a unchanged.
bool metricInside(const Metric& a, const Metric& b);

// Linear interpolation of Mt: (1 - t) Mt_a + t Mt_b, t in [0, 1].
Metric interpolate(const Metric& a, const Metric& b, double t);

// Weighted average of Mt over n metrics with nonnegative weights (sum > 0).
Metric weightedAverage(const Metric* metrics, const double* weights, int n);

// diff(M1, M2): the largest relative change of requested length over all directions,
// max(sqrt(mu_max), 1/sqrt(mu_min)) - 1 for the eigenvalues mu of M1^-1 M2. Zero iff equal.
double difference(const Metric& a, const Metric& b);

}  // namespace anisomesh

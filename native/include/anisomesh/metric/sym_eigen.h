#pragma once
// Closed-form eigen-decomposition of symmetric 2x2 matrices and its inverse, shared by the
// metric operations and the Hessian-based metrics (bit-identical everywhere: portable math).
#include "anisomesh/core/portable_math.h"
#include "anisomesh/core/types.h"

namespace anisomesh {

// Eigenvalues l1 >= l2 and the angle theta of l1's eigenvector.
struct SymEigen2 {
  double l1, l2, theta;
};

// The decomposition of m (its off-diagonal taken as the mean of the two), no iteration.
inline SymEigen2 symEigen(const Mat2& m) {
  const double a = m(0, 0), b = 0.5 * (m(0, 1) + m(1, 0)), c = m(1, 1);
  const double mean = 0.5 * (a + c), half = 0.5 * (a - c);
  const double r = pm::hypot(half, b);
  return {mean + r, mean - r, 0.5 * pm::atan2(2.0 * b, a - c)};
}

// The eigenvalues only (theta left 0): the same l1, l2 as symEigen() without its atan2,
// which costs more than the rest (most callers compare eigenvalues only).
inline SymEigen2 symEigenValues(const Mat2& m) {
  const double a = m(0, 0), b = 0.5 * (m(0, 1) + m(1, 0)), c = m(1, 1);
  const double mean = 0.5 * (a + c), half = 0.5 * (a - c);
  const double r = pm::hypot(half, b);
  return {mean + r, mean - r, 0.0};
}

// The symmetric matrix with eigenvalues l1, l2 and l1's eigenvector at angle theta.
inline Mat2 fromEigen(double l1, double l2, double theta) {
  const double c = pm::cos(theta), s = pm::sin(theta);
  Mat2 m;
  m(0, 0) = l1 * c * c + l2 * s * s;
  m(1, 1) = l1 * s * s + l2 * c * c;
  m(0, 1) = m(1, 0) = (l1 - l2) * c * s;
  return m;
}

}  // namespace anisomesh

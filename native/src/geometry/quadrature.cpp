#include "anisomesh/geometry/quadrature.h"

#include <cmath>

namespace anisomesh {
namespace {

constexpr double kNodes[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
constexpr double kWeights[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                                0.2369268850561891};

double refine(const std::function<double(double)>& f, double a, double b, double whole, double tol, int depth) {
  const double m = 0.5 * (a + b);
  const double left = gaussLegendre5(f, a, m), right = gaussLegendre5(f, m, b);
  if (depth <= 0 || std::abs(left + right - whole) <= tol * (1.0 + std::abs(left + right))) return left + right;
  return refine(f, a, m, left, 0.5 * tol, depth - 1) + refine(f, m, b, right, 0.5 * tol, depth - 1);
}

}  // namespace

double gaussLegendre5(const std::function<double(double)>& f, double a, double b) {
  const double h = 0.5 * (b - a), c = 0.5 * (a + b);
  double s = 0.0;
  for (int i = 0; i < 5; ++i) s += kWeights[i] * f(c + h * kNodes[i]);
  return s * h;
}

double integrateAdaptive(const std::function<double(double)>& f, double a, double b, double tol) {
  if (a == b) return 0.0;
  return refine(f, a, b, gaussLegendre5(f, a, b), tol, 18);
}

}  // namespace anisomesh

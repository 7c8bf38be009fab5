#pragma once
// Adaptive Gauss-Legendre quadrature used for (metric) curve lengths.
#include <functional>

namespace anisomesh {

// 5-point Gauss-Legendre rule on [a, b].
double gaussLegendre5(const std::function<double(double)>& f, double a, double b);

// Integral of f on [a, b], bisecting until the 5-point rule on an interval agrees with
// the sum over its halves within tol * (1 + |integral|) (depth-limited so it always ends).
double integrateAdaptive(const std::function<double(double)>& f, double a, double b, double tol);

}  // namespace anisomesh

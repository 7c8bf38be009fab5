#pragma once
// Metrics from recovered Hessians, the two families of solution-adaptive meshing:
//  - error level (BAMG's err): M = 2 c |H| / err with c = 2/9, so that a mesh whose edges
//    have metric lengths up to sqrt(2) (the mesher's bound) has a P1 interpolation error of
//    about err at most on every element (the bound |u - P1 u|_K <= c max_e e^T |H| e over
//    the element's edges e, Frey and Alauzet);
//    err is absolute, or relative to the field's range (max - min);
//  - target complexity (Loseille and Alauzet's continuous mesh, L^p norm, p = 1, 2, inf):
//    M_p = D (det |H|)^(-1/(2p+2)) |H|, the metric of complexity C = integral of
//    sqrt(det M) that minimizes the L^p interpolation error; D is set so that the
//    requested vertex count N is reached: C = N sqrt(3)/2 (a unit equilateral triangle has
//    metric area sqrt(3)/4, and a triangulation has about two triangles per vertex).
// Then, in both families: sizes clamped to [hmin, hmax], the larger size limited to
// anisomax times the smaller one (the small eigenvalue raised, as BAMG and MMG do); in
// target-complexity mode the scale D is found again after the clamps (bisection) so the
// clamped metric still has complexity C when [hmin, hmax] allows it. Several fields give
// one metric each, intersected vertex by vertex (metric intersection).
//
// Documented results: a field whose recovered Hessian is zero (constant or linear, within
// the recovery's rounding noise) gives the isotropic hmax at every vertex; hmax defaults
// to the mesh's bounding-box diagonal / 4, hmin to diagonal * 1e-6.
// Isotropic and uniform variants (for comparison, as in the examples' tables): isotropic
// takes the larger |eigenvalue| in both directions; uniform the same size everywhere with
// complexity C (target mode) or the smallest size of the isotropic error-level metric.
#include <cstdint>
#include <vector>

#include "anisomesh/adapt/hessian_recovery.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

enum class ErrorNorm { L1, L2, Linf };
enum class MetricShape { Anisotropic, Isotropic, Uniform };

struct FieldMetricOptions {
  // Exactly one of err > 0 (error level) or targetVertices > 0 (target complexity).
  double err = 0.0;
  bool relativeError = false;  // err relative to the field's range (max - min)
  double targetVertices = 0.0;
  ErrorNorm norm = ErrorNorm::Linf;  // target-complexity mode: the L^p norm minimized
  MetricShape shape = MetricShape::Anisotropic;
  double hmin = 0.0;                    // <= 0: diagonal * 1e-6
  double hmax = 0.0;                    // <= 0: diagonal / 4
  double anisomax = 1e3;                // largest ratio of requested sizes (>= 1)
  std::int64_t maxElements = 50000000;  // ElementBudgetExceeded when about 2 C / (sqrt(3)/2) triangles exceed it
  HessianRecoveryOptions recovery;
};

// The metric of one or several fields and what it implies.
struct FieldMetric {
  std::vector<Metric> metrics;    // one per vertex
  double complexity = 0.0;        // integral of sqrt(det M) over the mesh (P1 quadrature at vertices)
  double expectedVertices = 0.0;  // complexity * 2 / sqrt(3)
  double scale = 0.0;             // target mode: the factor D after the clamps
  double hmin = 0.0, hmax = 0.0;  // the bounds used (defaults resolved)
  std::vector<Mat2> absHessian;   // first field's |H| (floored), for error estimates
};

// |H| with its eigenvalues floored: |lambda| below noise taken as 0.
Mat2 absoluteHessian(const Mat2& h, double noise);

// Integral of sqrt(det M) over the mesh, each vertex weighted by a third of the area of its
// triangles (the complexity of the continuous mesh; about 0.87 vertices per unit).
double metricComplexity(const Mesh& mesh, const std::vector<Metric>& metrics);

// The metric of each field (recovered on mesh), intersected. Throws InvalidArgument for no
// field, neither or both of err/targetVertices, a bound out of range (hmin > hmax, anisomax
// < 1, norm), plus validateField's errors; ElementBudgetExceeded when the metric would
// need more than maxElements triangles (err too small or N too large).
FieldMetric metricFromFields(const Mesh& mesh, const std::vector<std::vector<double>>& fields,
                             const FieldMetricOptions& options);

// Same, from given Hessians (one set per field) and their noise levels.
FieldMetric metricFromHessians(const Mesh& mesh, const std::vector<std::vector<Mat2>>& hessians,
                               const std::vector<std::vector<double>>& noise, const std::vector<double>& ranges,
                               const FieldMetricOptions& options);

}  // namespace anisomesh

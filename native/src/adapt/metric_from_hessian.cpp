#include "anisomesh/adapt/metric_from_hessian.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/metric/sym_eigen.h"

namespace anisomesh {
namespace {

constexpr double kInterpolationConstant = 2.0 / 9.0;           // c of the P1 interpolation bound in 2D
constexpr double kVerticesPerComplexity = 1.1547005383792515;  // 2 / sqrt(3)
// The mesher accepts edges of metric length up to sqrt(2): the error-level metric asks for
// e^T M e = 1 on edges whose error bound c e^T |H| e is err / 2, so that edges at sqrt(2)
// still meet err.
constexpr double kLongestEdgeSquared = 2.0;

// The metric s * m (m symmetric positive semi-definite) with sizes clamped to [hmin, hmax]
// and the larger size at most anisomax times the smaller.
Metric clampedMetric(const Mat2& m, double s, double hmin, double hmax, double anisomax) {
  const SymEigen2 e = symEigen(m);
  auto size = [&](double l) {
    const double v = s * l;
    const double h = v > 0 ? 1.0 / std::sqrt(v) : hmax;
    return std::min(hmax, std::max(hmin, h));
  };
  const double h1 = size(e.l1), h2 = std::min(size(std::max(e.l2, 0.0)), anisomax * h1);
  return Metric::fromSizes(e.theta, h1, h2);
}

// sqrt(det) of clampedMetric(m, s, ...) without building it: 1 / (h1 h2).
double clampedDensity(const SymEigen2& e, double s, double hmin, double hmax, double anisomax) {
  auto size = [&](double l) {
    const double v = s * l;
    const double h = v > 0 ? 1.0 / std::sqrt(v) : hmax;
    return std::min(hmax, std::max(hmin, h));
  };
  const double h1 = size(e.l1), h2 = std::min(size(std::max(e.l2, 0.0)), anisomax * h1);
  return 1.0 / (h1 * h2);
}

// A third of the area of each vertex's triangles (P1 quadrature weights).
std::vector<double> vertexAreas(const Mesh& mesh) {
  std::vector<double> w(mesh.points.size(), 0.0);
  for (const auto& t : meshTriangles(mesh)) {
    const Vec3 &a = mesh.points[size_t(t[0])], &b = mesh.points[size_t(t[1])], &c = mesh.points[size_t(t[2])];
    const double area = 0.5 * std::abs((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
    for (int v : t) w[size_t(v)] += area / 3.0;
  }
  return w;
}

double boxDiagonal(const Mesh& mesh) {
  Vec2 lo = mesh.points[0].head<2>(), hi = lo;
  for (const Vec3& p : mesh.points) lo = lo.cwiseMin(p.head<2>()), hi = hi.cwiseMax(p.head<2>());
  return (hi - lo).norm();
}

}  // namespace

Mat2 absoluteHessian(const Mat2& h, double noise) {
  const SymEigen2 e = symEigen(h);
  auto a = [&](double l) { return std::abs(l) > noise ? std::abs(l) : 0.0; };
  return fromEigen(a(e.l1), a(e.l2), e.theta);
}

double metricComplexity(const Mesh& mesh, const std::vector<Metric>& metrics) {
  require(metrics.size() == mesh.points.size(), ErrorCode::InvalidArgument,
          "complexity: " + std::to_string(metrics.size()) + " metrics for " + std::to_string(mesh.vertexCount()) +
              " vertices");
  const std::vector<double> w = vertexAreas(mesh);
  double c = 0;
  for (size_t i = 0; i < w.size(); ++i) c += w[i] / metrics[i].sizeProduct();
  return c;
}

FieldMetric metricFromHessians(const Mesh& mesh, const std::vector<std::vector<Mat2>>& hessians,
                               const std::vector<std::vector<double>>& noise, const std::vector<double>& ranges,
                               const FieldMetricOptions& o) {
  require(!hessians.empty() && noise.size() == hessians.size() && ranges.size() == hessians.size(),
          ErrorCode::InvalidArgument, "metric from field: no field given");
  require((o.err > 0) != (o.targetVertices > 0), ErrorCode::InvalidArgument,
          "metric from field: give exactly one of err > 0 (error level) or a target vertex count N > 0");
  require(std::isfinite(o.err) && std::isfinite(o.targetVertices), ErrorCode::InvalidArgument,
          "metric from field: err and N must be finite");
  require(o.anisomax >= 1 && std::isfinite(o.anisomax), ErrorCode::InvalidArgument,
          "metric from field: anisomax must be a finite ratio >= 1, got " + std::to_string(o.anisomax));
  require(std::isfinite(o.hmin) && std::isfinite(o.hmax), ErrorCode::InvalidArgument,
          "metric from field: hmin and hmax must be finite");
  require(mesh.vertexCount() > 0 && mesh.elementCount() > 0, ErrorCode::InvalidArgument,
          "metric from field: the mesh has no triangles or quadrilaterals");
  const int n = mesh.vertexCount();
  for (size_t f = 0; f < hessians.size(); ++f)
    require(int(hessians[f].size()) == n && int(noise[f].size()) == n, ErrorCode::InvalidArgument,
            "metric from field: " + std::to_string(hessians[f].size()) + " Hessians for " + std::to_string(n) +
                " vertices");
  const double diag = boxDiagonal(mesh);
  FieldMetric out;
  out.hmin = o.hmin > 0 ? o.hmin : diag * 1e-6;
  out.hmax = o.hmax > 0 ? o.hmax : diag / 4;
  require(out.hmin <= out.hmax, ErrorCode::InvalidArgument,
          "metric from field: hmin " + std::to_string(out.hmin) + " exceeds hmax " + std::to_string(out.hmax));
  const double hmin = out.hmin, hmax = out.hmax;
  const double budgetVertices = double(o.maxElements) / 2.0;
  if (o.targetVertices > 0)
    require(o.targetVertices <= budgetVertices, ErrorCode::ElementBudgetExceeded,
            "metric from field: N = " + std::to_string(o.targetVertices) + " vertices would need about " +
                std::to_string(2 * o.targetVertices) + " triangles, above the element budget " +
                std::to_string(o.maxElements));
  const std::vector<double> area = vertexAreas(mesh);
  double totalArea = 0;
  for (double a : area) totalArea += a;
  const bool target = o.targetVertices > 0;
  const double complexity = target ? o.targetVertices / kVerticesPerComplexity : 0.0;
  const double p = o.norm == ErrorNorm::L1 ? 1.0 : o.norm == ErrorNorm::L2 ? 2.0 : INFINITY;

  // Per field: the floored |H|, shaped (isotropic: the larger eigenvalue both ways) and
  // limited to anisomax; then the unclamped metric of the family.
  std::vector<Mat2> combined(size_t(n), Mat2::Zero());
  for (size_t f = 0; f < hessians.size(); ++f) {
    const double floorRange = 1e-10 * ranges[f] / (diag * diag);
    std::vector<Mat2> m(static_cast<size_t>(n));
    double integral = 0;
    for (int i = 0; i < n; ++i) {
      SymEigen2 e = symEigen(absoluteHessian(hessians[f][size_t(i)], std::max(noise[f][size_t(i)], floorRange)));
      if (o.shape != MetricShape::Anisotropic) e.l2 = e.l1;
      e.l2 = std::max(e.l2, e.l1 / (o.anisomax * o.anisomax));
      const double det = e.l1 * e.l2;
      double factor = 1.0;
      if (target && std::isfinite(p)) factor = det > 0 ? pm::pow(det, -1.0 / (2 * p + 2)) : 0.0;
      if (!target)
        factor = kLongestEdgeSquared * kInterpolationConstant / (o.relativeError ? o.err * ranges[f] : o.err);
      if (!target && !(o.relativeError ? ranges[f] > 0 : true)) factor = 0.0;  // constant field, relative err
      m[size_t(i)] = fromEigen(factor * e.l1, factor * e.l2, e.theta);
      integral += area[size_t(i)] * factor * std::sqrt(det);
    }
    // Target mode: each field normalized to the complexity alone before intersecting.
    const double d = target ? (integral > 0 ? complexity / integral : 0.0) : 1.0;
    for (int i = 0; i < n; ++i) {
      const Mat2 mi = d * m[size_t(i)];
      if (f == 0) {
        combined[size_t(i)] = mi;
        continue;
      }
      // Intersection of semi-definite tensors through metrics with a tiny floor.
      const SymEigen2 a = symEigen(combined[size_t(i)]), b = symEigen(mi);
      if (b.l1 <= 0) continue;
      if (a.l1 <= 0) {
        combined[size_t(i)] = mi;
        continue;
      }
      const double tiny = 1e-300;
      const Metric x = intersect(Metric::fromTensor(fromEigen(std::max(a.l1, tiny), std::max(a.l2, tiny), a.theta)),
                                 Metric::fromTensor(fromEigen(std::max(b.l1, tiny), std::max(b.l2, tiny), b.theta)));
      combined[size_t(i)] = x.tensor();
    }
  }

  std::vector<SymEigen2> eig(static_cast<size_t>(n));
  double maxL1 = 0;
  for (int i = 0; i < n; ++i)
    eig[size_t(i)] = symEigen(combined[size_t(i)]), maxL1 = std::max(maxL1, eig[size_t(i)].l1);
  auto densityAt = [&](double s) {
    double c = 0;
    for (int i = 0; i < n; ++i) c += area[size_t(i)] * clampedDensity(eig[size_t(i)], s, hmin, hmax, o.anisomax);
    return c;
  };
  double s = 1.0;
  if (o.shape == MetricShape::Uniform) {
    // One size everywhere: target mode from the complexity, error mode the smallest size.
    double h = hmax;
    if (target)
      h = std::sqrt(totalArea / complexity);
    else if (maxL1 > 0)
      h = 1.0 / std::sqrt(maxL1);
    h = std::min(hmax, std::max(hmin, h));
    for (int i = 0; i < n; ++i) eig[size_t(i)] = {1.0 / (h * h), 1.0 / (h * h), 0.0};
  } else if (target && maxL1 > 0) {
    // Bisection on log s for densityAt(s) = complexity (monotone in s).
    double lo = 1.0, hi = 1.0;
    for (int k = 0; k < 200 && densityAt(lo) > complexity; ++k) lo *= 0.25;
    for (int k = 0; k < 200 && densityAt(hi) < complexity; ++k) hi *= 4.0;
    for (int k = 0; k < 50; ++k) {
      const double mid = std::sqrt(lo * hi);
      (densityAt(mid) < complexity ? lo : hi) = mid;
    }
    s = std::sqrt(lo * hi);
  }
  out.scale = s;
  out.metrics.reserve(size_t(n));
  for (int i = 0; i < n; ++i) {
    const SymEigen2& e = eig[size_t(i)];
    out.metrics.push_back(clampedMetric(fromEigen(e.l1, std::max(e.l2, 0.0), e.theta), s, hmin, hmax, o.anisomax));
  }
  out.complexity = 0;
  for (int i = 0; i < n; ++i) out.complexity += area[size_t(i)] / out.metrics[size_t(i)].sizeProduct();
  out.expectedVertices = out.complexity * kVerticesPerComplexity;
  require(out.expectedVertices <= budgetVertices, ErrorCode::ElementBudgetExceeded,
          "metric from field: the metric needs about " + std::to_string(std::llround(2 * out.expectedVertices)) +
              " triangles (complexity " + std::to_string(out.complexity) + "), above the element budget " +
              std::to_string(o.maxElements) + ": raise err or hmin");
  return out;
}

FieldMetric metricFromFields(const Mesh& mesh, const std::vector<std::vector<double>>& fields,
                             const FieldMetricOptions& options) {
  require(!fields.empty(), ErrorCode::InvalidArgument, "metric from field: no field given");
  std::vector<std::vector<Mat2>> hessians;
  std::vector<std::vector<double>> noise;
  std::vector<double> ranges;
  std::vector<Mat2> firstAbs;
  for (const auto& f : fields) {
    RecoveredDerivatives d = recoverHessian(mesh, f, options.recovery);
    hessians.push_back(std::move(d.hessian));
    noise.push_back(std::move(d.hessianNoise));
    const auto mm = std::minmax_element(f.begin(), f.end());
    ranges.push_back(*mm.second - *mm.first);
  }
  FieldMetric out = metricFromHessians(mesh, hessians, noise, ranges, options);
  out.absHessian.reserve(hessians[0].size());
  for (size_t i = 0; i < hessians[0].size(); ++i)
    out.absHessian.push_back(absoluteHessian(hessians[0][i], noise[0][i]));
  return out;
}

}  // namespace anisomesh

#include "anisomesh/adapt/adaptation_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "anisomesh/adapt/solution_transfer.h"
#include "anisomesh/core/clock.h"
#include "anisomesh/core/error.h"
#include "anisomesh/geometry/curve.h"

namespace anisomesh {
namespace {

constexpr double kP1InterpolationConstant = 2.0 / 9.0;

RemeshOptions remeshOptions(const FieldMetric& metric, const AdaptOptions& o) {
  RemeshOptions r;
  r.hmin = metric.hmin;
  r.hmax = metric.hmax;
  r.hgrad = o.hgrad;
  r.refineThreshold = o.refineThreshold;
  r.mesher.maxElements = o.metric.maxElements;
  r.mesher.improvementPasses = o.improvementPasses;
  return r;
}

// The loop; sample(mesh, previous mesh, previous fields) gives the fields on a new mesh.
AdaptResult runLoop(const Mesh& mesh, std::vector<std::vector<double>> fields, const AdaptOptions& o,
                    const std::function<std::vector<std::vector<double>>(
                        const Mesh&, const Mesh&, const std::vector<std::vector<double>>&)>& next,
                    const std::vector<FieldFunction>* functions) {
  // At most kMaxAdaptIterations (the CLI's -iterations range): the package has no callback
  // to stop a loop it was asked to run a billion times.
  require(o.iterations >= 1 && o.iterations <= kMaxAdaptIterations, ErrorCode::InvalidArgument,
          "adapt: iterations must be in [1, " + std::to_string(kMaxAdaptIterations) + "], got " +
              std::to_string(o.iterations));
  require(o.hgrad == 0 || (o.hgrad >= 1 && std::isfinite(o.hgrad)), ErrorCode::InvalidArgument,
          "adapt: hgrad must be 0 (off) or a ratio >= 1");
  AdaptResult result;
  result.mesh = mesh;
  result.fields = std::move(fields);
  // Vertices of a mesh made under a metric of continuous estimate V = C 2/sqrt(3): about
  // 1.05 V (measured on the four example functions, adapted meshes); then the ratio obtained.
  double correction = 1.0 / 1.05;
  for (int k = 0; k < o.iterations; ++k) {
    const auto t = Clock::now();
    AdaptIteration it;
    FieldMetricOptions mo = o.metric;
    if (mo.targetVertices > 0) mo.targetVertices *= correction;
    const FieldMetric metric = metricFromFields(result.mesh, result.fields, mo);
    it.secondsMetric = secondsSince(t);
    std::unique_ptr<AdaptiveControlSpace> cs;
    Mesh adapted = remesh(result.mesh, metric.metrics, remeshOptions(metric, o), &it.remesh, &cs);
    std::vector<std::vector<double>> adaptedFields = next(adapted, result.mesh, result.fields);
    // Target mode: the next metric asks for N times the ratio N / vertices obtained so far
    // (boundary vertices and the mesher's edge lengths make the count differ from the
    // continuous complexity by a few percent, about the same from one iteration to the next;
    // not after the first iteration, whose mesh did not resolve the field yet).
    if (o.metric.targetVertices > 0 && k > 0)
      correction = std::min(2.0, std::max(0.5, correction * o.metric.targetVertices / adapted.vertexCount()));
    it.vertices = adapted.vertexCount();
    it.triangles = int(adapted.triangles.size());
    it.complexity = metric.complexity;
    it.expectedVertices = metric.expectedVertices;
    const RecoveredDerivatives d = recoverHessian(adapted, adaptedFields[0], o.metric.recovery);
    std::vector<Mat2> absH;
    absH.reserve(d.hessian.size());
    for (size_t i = 0; i < d.hessian.size(); ++i) absH.push_back(absoluteHessian(d.hessian[i], d.hessianNoise[i]));
    it.estimatedError = estimatedInterpolationError(adapted, absH);
    if (functions) {
      const InterpolationError e = interpolationError(adapted, adaptedFields[0], (*functions)[0]);
      it.errorLinf = e.linf;
      it.errorL2 = e.l2;
    }
    result.mesh = std::move(adapted);
    result.fields = std::move(adaptedFields);
    result.controlSpace = std::move(cs);
    it.seconds = secondsSince(t);
    result.iterations.push_back(it);
    if (o.onIteration && !o.onIteration(k, result.mesh)) break;
  }
  return result;
}

}  // namespace

std::unique_ptr<AdaptiveControlSpace> fieldControlSpace(const Mesh& mesh, const FieldMetric& metric,
                                                        const AdaptOptions& options) {
  return buildRemeshControlSpace(mesh, metric.metrics, remeshOptions(metric, options));
}

std::vector<double> sampleField(const Mesh& mesh, const FieldFunction& f) {
  std::vector<double> v(mesh.points.size());
  for (size_t i = 0; i < v.size(); ++i) {
    v[i] = f(mesh.points[i].head<2>());
    if (!std::isfinite(v[i]))
      throw Error(ErrorCode::InvalidArgument, "field: the function is not finite at vertex " + std::to_string(i + 1) +
                                                  " " + formatPoint(mesh.points[i].head<2>()));
  }
  return v;
}

AdaptResult adaptToFields(const Mesh& mesh, const std::vector<std::vector<double>>& fields,
                          const AdaptOptions& options) {
  require(!fields.empty(), ErrorCode::InvalidArgument, "adapt: no field given");
  return runLoop(
      mesh, fields, options,
      [](const Mesh& to, const Mesh& from, const std::vector<std::vector<double>>& f) {
        return transferFields(from, f, to);
      },
      nullptr);
}

AdaptResult adaptToFunctions(const Mesh& mesh, const std::vector<FieldFunction>& functions,
                             const AdaptOptions& options) {
  require(!functions.empty(), ErrorCode::InvalidArgument, "adapt: no field given");
  auto sampleAll = [&functions](const Mesh& m) {
    std::vector<std::vector<double>> f;
    f.reserve(functions.size());
    for (const auto& fn : functions) f.push_back(sampleField(m, fn));
    return f;
  };
  return runLoop(
      mesh, sampleAll(mesh), options,
      [&](const Mesh& to, const Mesh&, const std::vector<std::vector<double>>&) { return sampleAll(to); }, &functions);
}

InterpolationError interpolationError(const Mesh& mesh, const std::vector<double>& values, const FieldFunction& f) {
  validateField(mesh, values);
  // Dunavant's degree-5 rule (7 points) for L2, a barycentric lattice of order 6 for L-inf.
  static const double kRule[7][4] = {{1.0 / 3, 1.0 / 3, 1.0 / 3, 0.225},
                                     {0.0597158717897698, 0.4701420641051151, 0.4701420641051151, 0.1323941527885062},
                                     {0.4701420641051151, 0.0597158717897698, 0.4701420641051151, 0.1323941527885062},
                                     {0.4701420641051151, 0.4701420641051151, 0.0597158717897698, 0.1323941527885062},
                                     {0.7974269853530873, 0.1012865073234563, 0.1012865073234563, 0.1259391805448271},
                                     {0.1012865073234563, 0.7974269853530873, 0.1012865073234563, 0.1259391805448271},
                                     {0.1012865073234563, 0.1012865073234563, 0.7974269853530873, 0.1259391805448271}};
  InterpolationError e;
  double sum = 0;
  for (const auto& t : meshTriangles(mesh)) {
    const Vec2 a = mesh.points[size_t(t[0])].head<2>(), b = mesh.points[size_t(t[1])].head<2>(),
               c = mesh.points[size_t(t[2])].head<2>();
    const double fa = values[size_t(t[0])], fb = values[size_t(t[1])], fc = values[size_t(t[2])];
    const double area = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    auto diff = [&](double l0, double l1, double l2) {
      return f(l0 * a + l1 * b + l2 * c) - (l0 * fa + l1 * fb + l2 * fc);
    };
    double s = 0;
    for (const auto& r : kRule) {
      const double d = diff(r[0], r[1], r[2]);
      s += r[3] * d * d;
      e.linf = std::max(e.linf, std::abs(d));
    }
    sum += area * s;
    for (int i = 0; i <= 6; ++i)
      for (int j = 0; i + j <= 6; ++j) e.linf = std::max(e.linf, std::abs(diff(i / 6.0, j / 6.0, (6 - i - j) / 6.0)));
  }
  e.l2 = std::sqrt(sum);
  return e;
}

double estimatedInterpolationError(const Mesh& mesh, const std::vector<Mat2>& absHessian) {
  require(absHessian.size() == mesh.points.size(), ErrorCode::InvalidArgument,
          "error estimate: one Hessian per vertex expected");
  double worst = 0;
  for (const auto& t : meshTriangles(mesh)) {
    const Mat2 h = (absHessian[size_t(t[0])] + absHessian[size_t(t[1])] + absHessian[size_t(t[2])]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      const Vec2 e = (mesh.points[size_t(t[(k + 1) % 3])] - mesh.points[size_t(t[k])]).head<2>();
      worst = std::max(worst, e.dot(h * e));
    }
  }
  return kP1InterpolationConstant * worst;
}

}  // namespace anisomesh

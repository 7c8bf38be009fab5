#pragma once
// The adaptation loop: K times, recover the Hessians of the fields on the current mesh,
// build their metric (metric_from_hessian.h) as a background-mesh control space, remesh
// the domain bounded by the current mesh's boundary under it (pipeline.h remesh, gradation
// hgrad through the control space's anisotropic smoothing), and carry the fields over:
// fields given as values are transferred (solution_transfer.h); fields given as
// functions (the expression language in x, y) are re-sampled exactly on each new mesh.
// Each iteration reports the mesh size, the metric's complexity and the estimated P1
// interpolation error (and, for functions, the actual L-inf and L2 errors). In target mode
// the metric asks for N / 1.05 (the mesher makes about 1.05 times the continuous estimate
// C 2/sqrt(3) on adapted meshes: boundary vertices, edge lengths), and from the third
// iteration on for N times the ratio of N to the vertices the previous iterations obtained,
// so the meshes hold about N vertices.
#include <functional>
#include <memory>
#include <vector>

#include "anisomesh/adapt/metric_from_hessian.h"
#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/pipeline/pipeline.h"

namespace anisomesh {

inline constexpr int kMaxAdaptIterations = 1000;

struct AdaptOptions {
  FieldMetricOptions metric;     // err or targetVertices, norm, hmin, hmax, anisomax, budget
  int iterations = 3;            // K in [1, kMaxAdaptIterations]
  double hgrad = 0.0;            // gradation ratio dr of the control space (0: off, else >= 1)
  double refineThreshold = 1.0;  // control space: metric difference that splits an element (remesh uses 0.2;
                                 // field metrics vary from vertex to vertex, 1 keeps the structure ~7x the mesh)
  int improvementPasses = 4;     // planar mesher adaptation rounds
  // Called after each iteration with its index (0-based) and mesh; returning false stops
  // the loop (the result holds the iterations done so far).
  std::function<bool(int, const Mesh&)> onIteration;
};

// One iteration's figures.
struct AdaptIteration {
  int vertices = 0;
  int triangles = 0;
  double complexity = 0.0;        // of the metric the mesh was built under
  double expectedVertices = 0.0;  // complexity * 2 / sqrt(3)
  double estimatedError = 0.0;    // c max over triangles of max_e e^T |H| e on the new mesh (first field)
  double errorLinf = -1.0;        // functions only: max |f - P1 f| (sampled, 28 points per triangle); else -1
  double errorL2 = -1.0;          // functions only: L2 norm of f - P1 f (degree-5 rule); else -1
  double seconds = 0.0;           // wall time of the iteration
  double secondsMetric = 0.0;     // of which Hessian recovery and metric
  PipelineReport remesh;          // the remeshing run (control space, discretization, meshing times)
};

struct AdaptResult {
  Mesh mesh;                                // the last mesh
  std::vector<std::vector<double>> fields;  // the fields at its vertices
  std::vector<AdaptIteration> iterations;
  std::unique_ptr<AdaptiveControlSpace> controlSpace;  // the last iteration's control space
};

// A field given as a function of the point.
using FieldFunction = std::function<double(const Vec2&)>;

// The background-mesh control space of a field metric on mesh (buildRemeshControlSpace):
// composes with geometric and user sources by the section 2.4 minimum
// (MinimumControlSpace or intersectControlSpace).
std::unique_ptr<AdaptiveControlSpace> fieldControlSpace(const Mesh& mesh, const FieldMetric& metric,
                                                        const AdaptOptions& options = {});

// Adapts to fields given at the vertices of mesh (transferred between iterations). Throws
// what validateField, metricFromFields and remesh throw; InvalidArgument for iterations outside [1,
// kMaxAdaptIterations].
AdaptResult adaptToFields(const Mesh& mesh, const std::vector<std::vector<double>>& fields,
                          const AdaptOptions& options);

// Adapts to functions, sampled on mesh and re-sampled on every new mesh; a sample that is
// not finite throws InvalidArgument naming the point.
AdaptResult adaptToFunctions(const Mesh& mesh, const std::vector<FieldFunction>& functions,
                             const AdaptOptions& options);

// Values of f at the vertices of mesh (InvalidArgument on a non-finite value).
std::vector<double> sampleField(const Mesh& mesh, const FieldFunction& f);

// L-inf and L2 norms of f - P1 interpolant of values over mesh's triangles.
struct InterpolationError {
  double linf = 0.0;
  double l2 = 0.0;
};
InterpolationError interpolationError(const Mesh& mesh, const std::vector<double>& values, const FieldFunction& f);

// c max over triangles of max over its edges e of e^T |H| e, |H| averaged over its vertices.
double estimatedInterpolationError(const Mesh& mesh, const std::vector<Mat2>& absHessian);

}  // namespace anisomesh

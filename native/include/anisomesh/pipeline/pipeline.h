#pragma once
// End-to-end runs: a JSON case (validate domain -> control space -> contour
// discretization -> section 3.2 control-space updates -> planar mesher) and remeshing of
// a Medit mesh under a .sol metric (background-mesh control space).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "anisomesh/boundary/boundary_updates.h"
#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"
#include "anisomesh/pipeline/case_model.h"
#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {

// What a run did, for --stats and logs.
struct PipelineReport {
  int boundaryLoops = 0;
  int boundaryPoints = 0;
  double secondsGeometry = 0.0;        // domain validation (remesh: boundary extraction too)
  double secondsControlSpace = 0.0;    // building the control space
  double secondsDiscretization = 0.0;  // contour discretizations (all rounds)
  double secondsUpdates = 0.0;         // section 3.2 loop: boundary-only meshes and checks
  double secondsMeshing = 0.0;         // final meshPlanarBoundary
  int controlElements = 0;             // elements of the control structure at the end
  int controlNodes = 0;
  // Section 3.2 loop.
  int updateRounds = 0;            // rounds run (1 = the first discretization was valid)
  bool updatesConverged = true;    // false when the round limit stopped the loop
  int shortSegments = 0;           // boundary segments with metric length < eps1 (all rounds)
  int shortSegmentSources = 0;     // sources added along them (the segment's length as reference)
  int invalidSegments = 0;         // ... with length < 1/2 or > 2 (their contour is invalid)
  int rediscretizedContours = 0;   // contours discretized again after the first round
  int chordSources = 0;            // curvature sources added for chord deviation
  int proximitySources = 0;        // sources added for thin boundary triangles
  int refinedElements = 0;         // control elements added near short segments
  double maxChordDeviation = 0.0;  // largest deviation / chord length over curved contours, last round
  long long cacheHits = 0;         // section 4 query cache (when on): queries answered by it
  long long cacheMisses = 0;       // ... and passed to the control space
  MesherTimings mesherTimings;     // stages of the final meshPlanarBoundary
  std::vector<std::string> notes;
};

// The mesher options of a case (quads, allQuads, maxElements).
PlanarMesherOptions mesherOptionsFromCase(const CaseSpec& spec);

// Meshes a case: validateDomain, buildCaseControlSpace, then rounds of discretizeDomain
// + boundary-only triangulation + section 3.2 updates until nothing is invalid, then
// meshPlanarBoundary. When controlSpace is given it receives the final control space
// (for quality measurement). progress (optional) follows the final meshing; returning
// false cancels the run (ErrorCode::Cancelled).
Mesh meshCase(const CaseSpec& spec, PipelineReport* report = nullptr, const BoundaryUpdateOptions& updates = {},
              std::unique_ptr<AdaptiveControlSpace>* controlSpace = nullptr,
              const std::function<bool(double)>& progress = {});

// How the input's per-vertex metrics enter the background-mesh control space.
enum class RemeshMetricInsertion {
  // Continuous source (section 2.3): Mt interpolated linearly over the input triangles
  // (TriangleMeshMetricField) evaluated at the control nodes, elements split where it
  // varies by more than refineThreshold. Default: on the peer benchmark it follows the
  // input metric much better (99.8% vs 95.2% unit edges at scale 1).
  PiecewiseLinear,
  // Discrete NodeSource (section 2.2): structure refined to each vertex's size near it,
  // weighted averages of the vertices reaching a control node, extrapolation.
  NodeSource,
};

struct RemeshOptions {
  double hmin = 0.0;   // clamp every requested size to >= hmin (0: off)
  double hmax = 0.0;   // clamp every requested size to <= hmax (0: off)
  double hgrad = 0.0;  // gradation ratio dr of the control space smoothing (0: off, else >= 1)
  RemeshMetricInsertion insertion = RemeshMetricInsertion::PiecewiseLinear;
  double refineThreshold = 0.2;  // PiecewiseLinear: metric difference that splits a control element
  // PiecewiseLinear: control elements below this times the smallest requested size at their
  // nodes are not split, so the control space grows with the output, not with the carrier
  // (0: split down to the carrier's resolution).
  double refineMinMetricSize = 0.5;
  double queryCache = 0.0;           // section 4 query cache tolerance (metric distance); 0: off
  std::int64_t maxControlNodes = 0;  // control-space node budget; 0: controlSpaceNodeBudget(mesher.maxElements)
  // MMG's -hausd: > 0: the boundary between corners is a C1 spline through the input's
  // boundary vertices (SplineCurve), re-discretized under the metric with every chord within
  // this distance of it (curvature sources, section 3.2 (b), until none is farther, at most
  // 8 rounds); 0: the input's boundary polyline.
  double hausdorff = 0.0;
  // MMG's -ar, radians: boundary vertices turning by more than this are corners (reference
  // changes always are); >= pi: no angle corners (-nr); < 0: the default, pi/4 (MMG's 45
  // degrees) with hausdorff, 0.5 for the polyline boundary.
  double ridgeAngle = -1.0;
  PlanarMesherOptions mesher;
  // Called as each stage starts ("boundary", "control space", "discretization", "meshing"):
  // progress lines and per-stage timings (CLI -v).
  std::function<void(const char* stage)> onStage;
};

// The background-mesh control space of a remeshing run (buildAdaptiveControlSpace with
// kind BackgroundMesh): the input metrics inserted as options.insertion says, clamped to
// [hmin, hmax], smoothed with hgrad (section 2.5). Throws InvalidArgument on a count
// mismatch or an input without triangles (PiecewiseLinear).
std::unique_ptr<AdaptiveControlSpace> buildRemeshControlSpace(const Mesh& input, const std::vector<Metric>& metrics,
                                                              const RemeshOptions& options = {});

// Remeshes the domain bounded by the input mesh's boundary loops under the per-vertex
// metrics (through buildRemeshControlSpace); boundary refs are kept. When controlSpace
// is given it receives the control space used.
Mesh remesh(const Mesh& input, const std::vector<Metric>& metrics, const RemeshOptions& options = {},
            PipelineReport* report = nullptr, std::unique_ptr<AdaptiveControlSpace>* controlSpace = nullptr);
// The same, consuming the input and its metrics: both are freed as soon as the boundary
// loops and the control space are built, before the contours are discretized and the
// domain meshed (the memory peak of large remeshing runs; the same mesh).
Mesh remesh(Mesh&& input, std::vector<Metric>&& metrics, const RemeshOptions& options = {},
            PipelineReport* report = nullptr, std::unique_ptr<AdaptiveControlSpace>* controlSpace = nullptr);

// Meshes a surface case (meshSurfaceModel with the case's options).
Mesh meshSurfaceCase(const SurfaceCaseSpec& spec, SurfaceMeshReport* report = nullptr);

}  // namespace anisomesh

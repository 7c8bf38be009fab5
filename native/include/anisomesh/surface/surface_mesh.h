#pragma once
// Anisotropic meshing of 3D surface patches (paper section 3, Algorithm 1). Every patch
// is meshed in its parameter plane (u, v) with its own adaptive quadtree control space:
// the curvature metric pulled back through J (M_uv = J^T M3 J), intersected with user
// sources, smoothed for gradation. Patches share boundary curves: a shared curve is
// discretized once in 3D (at each point the stricter of the patches' metrics) and mapped
// into each patch's plane, so the merged mesh is conforming (shared vertices have one index).
//
// Gradation note: smoothing runs on each patch's quadtree in the parameter plane, so the
// ratio dr bounds the growth of parameter-space sizes per parameter-space distance. For a
// parameterization with nearly constant stretching (|Mp| slowly varying) that is the 3D
// bound; where Mp varies strongly the 3D growth differs by the local stretch ratio.
#include <memory>
#include <string>
#include <vector>

#include "anisomesh/boundary/boundary_updates.h"
#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/controlspace/metric_sources.h"
#include "anisomesh/controlspace/parameterized_control_space.h"
#include "anisomesh/geometry/domain.h"
#include "anisomesh/geometry/surface.h"
#include "anisomesh/geometry/surface_metric.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"

namespace anisomesh {

namespace surface_mesher {
struct DeferredMeasures;  // a run's 3D measures, not yet made (surface_measures.cpp)
}

// An isotropic size h requested within `radius` of a 3D point (applies to every patch).
struct Source3D {
  Vec3 center = Vec3::Zero();
  double h = 1.0;
  double radius = 0.0;
};

// One trimmed patch: the surface and, in its (u, v) plane, the outer contour and holes.
struct SurfacePatch {
  std::shared_ptr<const Surface> surface;
  Domain domain;
  int id = 0;                         // triangle reference of the patch's elements
  std::string name;                   // used in error messages
  std::vector<MetricSource> sources;  // user metric sources in (u, v)
};

// Where a curve sits in a patch: contour 0 = outer, k + 1 = hole k; curve index in that contour.
struct CurveRef {
  int patch = 0;
  int contour = 0;
  int curve = 0;
};

// Two boundary curves that are one curve in 3D; reversed: a.start meets b.end.
struct SharedCurve {
  CurveRef a, b;
  bool reversed = false;
};

struct SurfaceModel {
  std::vector<SurfacePatch> patches;
  std::vector<SharedCurve> shared;
  std::vector<Source3D> sources3d;
};

// Default SurfaceMeshOptions::chordSafety = sqrt(8/3). Near a point, in the tangent plane's
// principal frame, the surface deviates from it by d(x) = (k1 x1^2 + k2 x2^2) / 2. With sizes
// h_i = sqrt(8 t / (s^2 |k_i|)) and metric coordinates y_i = x_i / h_i, |d| <= 4 t |y|^2 / s^2.
// A flat triangle through three surface points deviates from the quadratic most at its
// circumcentre (acute) or at the midpoint of its longest edge (obtuse): 4 t R^2 / s^2 with R
// the metric circumradius, and R <= L / sqrt3 for the longest metric edge L. The mesher
// accepts edges up to L = sqrt2, so R^2 <= 2/3 and the deviation is <= (8/3) t / s^2; s^2 = 8/3
// keeps it within t (edges alone: L^2 t / s^2 <= 3/4 t). Sizes then are sqrt(3/8) = 0.61 of
// the paper's sqrt(8 t / |k|), about 8/3 times the elements.
inline constexpr double kDefaultChordSafety = 1.6329931618554521;

struct SurfaceMeshOptions {
  SurfaceMetricOptions metric;  // chord tolerance, hmin, hmax, d_max (3D)
  // Sizes come from chordTolerance / chordSafety^2: h = sqrt(8 tol / (chordSafety^2 |k|)).
  // The default sqrt(8/3) gives h = sqrt(3 tol / |k|), which keeps the whole mesh (edges and
  // triangle interiors) within tol when edges reach metric length sqrt2; 1 is the paper's
  // sizing (edges of metric length 1 have sagitta tol). Derivation in kDefaultChordSafety.
  double chordSafety = kDefaultChordSafety;
  double gradation = 2.0;  // dr in the parameter plane; 0 = off
  // Section 3.1: sizes from the 3D curvature of every contour curve put into the initial
  // control space along it (false: only the section 3.2 chord check catches contour curvature).
  bool contourCurvature = true;
  bool adaptation = true;  // adjust control spaces of adjacent patches (figs. 11-13)
  int maxRounds = 4;       // bound of Algorithm 1's invalidation loop
  // Section 3.2 thresholds (eps1, [lengthMin, lengthMax], eps2, dMax), the same rules as planar
  // cases; the contour chord is checked in 3D against metric.chordTolerance instead of chordTolerance.
  BoundaryUpdateOptions boundary;
  int initialLevel = 3;           // quadtree main-level grid 2^initialLevel
  int maxLevel = 12;              // deepest quadtree level
  double refineThreshold = 0.25;  // difference() between node metrics that splits a leaf
  double sharedTolerance = 1e-6;  // shared curves must match within this * model size
  PlanarMesherOptions mesher;     // inner nodes and improvement (its quads / allQuads are ignored)
  // Node budget of each patch's control space; 0: controlSpaceNodeBudget(mesher.maxElements).
  std::int64_t maxControlNodes = 0;
  // Section 4.3: what the mesher's queries read. Folded: each node's (u, v) metric; Stored:
  // each node's tangent-plane Mt and Mp, both interpolated; Computed: Mt interpolated, Mp
  // from the surface at every query (see controlspace/parameterized_control_space.h).
  ParameterizationStorage parameterization = ParameterizationStorage::Folded;
  // Quad-dominant: triangle pairs merged in each patch's (u, v) (metric quality >= mesher.minQuadQuality);
  // shared contour edges are never merged across, so the patches stay conforming.
  bool quads = false;
  // All-quad: then every element split (midpoints of edges shared by all elements using
  // them, boundary edges split at the contour curve's middle parameter).
  bool allQuads = false;
  bool mergeMesh = true;  // false: keep patches' vertices separate (debugging)
  // Flip whole patches so the merged mesh has one 3D orientation across shared curves;
  // a flipped patch's triangles are then clockwise in its own (u, v).
  bool consistentOrientation = true;
  bool measureQuality = true;  // fill SurfaceMeshReport::quality (3D measures cost about a mesh run)
  // With measureQuality and a report: the run leaves its 3D measures to measureSurfaceElements()
  // and finishSurfaceMeasures() (SurfaceMeshReport::deferred), so a caller can draw the mesh first.
  bool deferQuality = false;
  bool controlSpaceGlyphs = false;  // fill SurfaceMeshReport::controlSpaceGlyphs (pictures)
};

// The requested metric drawn at one control element (quadtree leaf) of a patch: the
// ellipse {c + 0.5 Mt^-1 (cos a, sin a)} around the leaf centre c inside the patch (half
// of the requested sizes along its axes), in (u, v) and mapped through S.
struct ControlSpaceGlyph {
  int patch = 0;
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
};

// 3D quality of a surface mesh in the requested metric (each patch's control space,
// pulled forward into 3D; shared edges counted once).
struct Surface3DQuality {
  int edges = 0;
  double edgesWithinSqrt2 = 0.0;  // fraction of edges with 3D metric length in [1/sqrt2, sqrt2]
  double edgeLengthMin = 0.0, edgeLengthMean = 0.0, edgeLengthMax = 0.0;
  double qualityMean = 0.0, qualityMin = 0.0;  // triangleQuality3D
  // Largest mesh-to-surface gap along the surface normal: at samples of every edge and of
  // every triangle's interior (barycentric points, centroid included), the distance between
  // the point of the flat 3D triangle and the tangent plane at the surface point of the same
  // parameter (first order the distance to the surface, without the tangential offset).
  double chordDeviationMax = 0.0;
  double edgeChordDeviationMax = 0.0;      // the same over edges only
  double isoChordDeviationMax = 0.0;       // chordDeviation(): to the image of the parameter segment
  double chordDeviationMaxRelative = 0.0;  // the same divided by the chord tolerance
  int inverted = 0;                        // clockwise triangles in their patch's (u, v)
};

// The 3D metric length of one merged-mesh edge (vertices a < b) as the report measures it
// (Simpson's rule over the edge in its patch's control space).
struct SurfaceEdgeLength {
  int a = 0, b = 0;
  double length = 0.0;
};

struct SurfaceMeshReport {
  int patches = 0;
  int rounds = 0;         // Algorithm 1 rounds (discretizations) of the section 3.2 loop
  int invalidations = 0;  // contour invalidations over all rounds
  bool converged = true;  // false: the section 3.2 loop stopped at options.maxRounds
  // Section 3.2 control-space updates over all rounds and patches (the rules of boundary_updates.h).
  int chordSources = 0, proximitySources = 0, shortSegmentSources = 0;
  int vertices = 0, triangles = 0;
  int sharedEdges = 0;                   // mesh edges on shared curves
  double crossSharedSizeRatioMax = 0.0;  // largest sqrt(area) ratio of the two triangles at a shared edge
  Surface3DQuality quality;
  // Cost counters: curvature metric evaluations (building the control spaces) and
  // control space queries (discretization and meshing), with their times.
  long long curvatureEvaluations = 0;
  double curvatureSeconds = 0.0;
  long long controlSpaceQueries = 0;
  double controlSpaceSeconds = 0.0;
  double secondsTotal = 0.0;
  std::vector<int> patchTriangles;                 // per patch
  std::vector<std::array<int, 2>> sharedEdgeList;  // merged-mesh vertex pairs (i < j) on shared curves
  std::vector<double> elementQuality;  // 3D quality of each element (triangles, then quads), with measureQuality
  std::vector<SurfaceEdgeLength> edgeLengths;         // every distinct edge's 3D metric length, with measureQuality
  std::vector<ControlSpaceGlyph> controlSpaceGlyphs;  // final control spaces, with options.controlSpaceGlyphs
  // With options.deferQuality: the patch meshes and control spaces the 3D measures read,
  // kept until finishSurfaceMeasures() (quality, elementQuality, edgeLengths and the
  // controlSpaceQueries they add are unset until then).
  std::shared_ptr<surface_mesher::DeferredMeasures> deferred;
};

// A run made with SurfaceMeshOptions::deferQuality: fills report.elementQuality and
// report.edgeLengths (the per-element measures, which make every control-space query of
// the measures) from report.deferred; no-op without it.
void measureSurfaceElements(SurfaceMeshReport& report);

// The same, then everything else measureQuality fills (quality: chord deviations,
// inverted elements; controlSpaceQueries/Seconds), as a run without deferQuality would
// have filled it; drops report.deferred. No-op without it.
void finishSurfaceMeasures(SurfaceMeshReport& report);

// Meshes every patch of the model (Algorithm 1) and merges them into one 3D Mesh:
// points = S(u, v), params = (u, v) of the first patch using the vertex, triangleRefs =
// patch ids, edges = boundary edges of the merged mesh (non-shared contours).
// Errors: InvalidSurface (shared curves not matching, NaN/degenerate parameterization,
// naming the patch and the (u, v) place), InvalidDomain (contour off the patch domain).
Mesh meshSurfaceModel(const SurfaceModel& model, const SurfaceMeshOptions& options = {},
                      SurfaceMeshReport* report = nullptr);

// One patch (a model with a single patch and no sharing).
Mesh meshSurfacePatch(const SurfacePatch& patch, const SurfaceMeshOptions& options = {},
                      SurfaceMeshReport* report = nullptr);

// The initial control space of a patch (section 3.1): curvature metric sampled into an
// adaptive quadtree (extrapolated where the parameterization is degenerate), user
// sources, contour curvature sources, 3D sources, size clamps, gradation. Exposed for tests and the benchmark.
std::unique_ptr<AdaptiveControlSpace> buildPatchControlSpace(const SurfacePatch& patch,
                                                             const std::vector<Source3D>& sources3d,
                                                             const SurfaceMeshOptions& options);

// The 3D tangent metric equivalent to the (u, v) metric m at a point with derivatives d:
// T = J+^T M J+ on the tangent plane plus n n^T / hn^2 (hn the smallest size).
Mat3 metric3DFromParameter(const Metric& m, const SurfaceDerivatives& d);

// Largest ratio sqrt(area) of the two elements (triangles or quads) at each edge listed (3D areas); 0 if none.
double acrossEdgeSizeRatio(const Mesh& mesh, const std::vector<std::array<int, 2>>& edges);

// Boundary edges (used by one element) of a mesh, sorted pairs (i < j).
std::vector<std::array<int, 2>> openEdges(const Mesh& mesh);

}  // namespace anisomesh

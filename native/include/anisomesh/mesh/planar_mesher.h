#pragma once
// Metric Delaunay meshing of a planar domain (or a patch's parameter domain) whose
// contours are already discretized: boundary triangulation, boundary recovery,
// insertion of inner nodes until edges have metric length near 1, improvement.
//
// Method (coordinate transformation): each triangle carries the average Mt of its
// vertices; its circumcircle, acceptance (metric circumradius <= 1/sqrt2) and the
// Bowyer-Watson cavity test are evaluated in that metric space. Inner nodes are placed
// frontally (Rebay): from a front edge, at the distance that makes a unit equilateral
// triangle in the metric. Then an adaptation loop in the metric (MMG/BAMG style): edge
// swaps maximizing the worse triangle's quality, collapse of edges shorter than 1/sqrt2
// and split of inner edges longer than sqrt2, node smoothing (metric queried at the new
// position, no edge made longer than sqrt2 or shorter than 1/sqrt2), then final rounds
// collapsing the edges still shorter than 1/sqrt2 (merged vertex at unit length from its
// ring); boundary points and edges are never moved or split. Topological
// decisions use exact predicates (predicates.h). Output is deterministic bit for bit.
//
// Output: boundary points first (loop by loop, input order, unchanged), then inner
// nodes; boundary edges in input order with their refs; triangles counter-clockwise,
// refs 0. With quads: greedy merge of triangle pairs (quad metric quality >= 0.3).
// With allQuads: every element split into quads (mesh/all_quad_split.h); boundary edges
// are split at the loops' edgeMidpoints (on the contour curve) or, without them, at the
// straight midpoint, and the result has edges of about half the requested metric length (discretize the contours
// at twice the size to get unit quads).
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/geometry/boundary_loop.h"
#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

// Wall-clock seconds spent in each stage of one meshPlanarBoundary run, and the element
// estimate used for the budget check (copied into QualityReport by the caller).
struct MesherTimings {
  double boundary = 0.0;     // boundary triangulation, recovery, outside removal
  double insertion = 0.0;    // inner node insertion
  double improvement = 0.0;  // edge swaps and node smoothing
  double quads = 0.0;        // quad conversion
  std::int64_t estimatedElements = 0;
  int parts = 1;                   // domain decomposition parts (the stage times are then sums over them)
  bool boundaryFromCache = false;  // the boundary triangulation came from options.boundaryCache
};

// The boundary triangulation of a boundary-only run (a section 3.2 check), kept for the
// full run that follows on the same loops (opaque; see PlanarMesherOptions::boundaryCache).
struct BoundaryTriangulationCache;
std::shared_ptr<BoundaryTriangulationCache> makeBoundaryTriangulationCache();

struct PlanarMesherOptions {
  bool quads = false;                   // convert to a quad-dominant mesh
  bool allQuads = false;                // then split into an all-quad mesh
  std::int64_t maxElements = 50000000;  // element budget: ElementBudgetExceeded above it
  int improvementPasses = 4;            // adaptation rounds in the metric: swaps, collapse/split, smoothing
  bool boundaryOnly = false;            // stop after the boundary triangulation (section 3.2 checks)
  // Called with a fraction in [0, 1]; returning false cancels the run (ErrorCode::Cancelled).
  std::function<bool(double)> progress;
  // Candidate inner nodes closer than this (metric length) to an existing vertex are rejected.
  double minNodeDistance = 0.6;
  // Quad-dominant merge: pairs whose quad would have a lower metric quality stay triangles.
  double minQuadQuality = 0.3;
  MesherTimings* timings = nullptr;  // optional output: stage times
  // Domain decomposition (mesh/domain_decomposition.h): domains estimated at 2 x this many
  // elements or more are split into parts of about this size, meshed concurrently and merged;
  // 0 meshes the domain whole. Not with boundaryOnly or allQuads. Small parts are also
  // faster on one thread (their data stays in cache): at 1e6 triangles, 32 parts of ~30k
  // mesh in ~60 % of the time 4 parts of 250k take (native/bench/remesh_throughput.mjs).
  std::int64_t partElements = 15000;
  // Optional: a boundary-only run leaves its boundary triangulation here, and the next full
  // run on loops equal to its own takes it (moved, used once) instead of building it again:
  // the same mesh. Not shared between runs that may overlap in time.
  std::shared_ptr<BoundaryTriangulationCache> boundaryCache;
};

// Meshes the region inside loops[0] and outside loops[1..]; every boundary point is a
// mesh vertex and every boundary edge is a mesh edge (with its reference).
Mesh meshPlanarBoundary(const std::vector<BoundaryLoop>& loops, const ControlSpace& controlSpace,
                        const PlanarMesherOptions& options = {});

}  // namespace anisomesh

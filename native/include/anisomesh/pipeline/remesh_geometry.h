#pragma once
// The geometry of a remeshing run: the boundary of an input mesh chained into closed
// loops (keeping edge references), turned into a domain of polyline curves.
#include <vector>

#include "anisomesh/geometry/domain.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

// Boundary edges of the mesh chained into closed loops: the element edges used once
// (refs from the matching Edges entry, else 0), or the Edges themselves when the mesh
// has no elements. loops[0] is the outer loop (largest area, counter-clockwise), the
// others holes (clockwise). Throws OpenContour when the edges do not form closed loops,
// InvalidDomain for nested loops (islands) or a non-planar mesh.
std::vector<BoundaryLoop> boundaryLoopsFromMesh(const Mesh& mesh);

struct LoopDomainOptions {
  // A vertex whose direction turns by more than this (radians) is a corner: it stays a
  // boundary point (MMG's -ar; >= pi: no angle corners, MMG's -nr).
  double cornerAngle = 0.5;
  // The pieces become C1 splines through the loop's vertices (SplineCurve, joined C1 where
  // a smooth loop is only split), else polylines (MMG's -hausd reconstruction).
  bool smooth = false;
};

// A domain whose curves are the loops split where the edge reference changes and at
// corners; each piece is a polyline whose inner vertices may be moved across, or a spline.
Domain domainFromBoundaryLoops(const std::vector<BoundaryLoop>& loops, const LoopDomainOptions& options = {});

// The metrics with their requested sizes clamped to [hmin, hmax] (a bound <= 0 is off).
std::vector<Metric> clampMetricSizes(const std::vector<Metric>& metrics, double hmin, double hmax);

}  // namespace anisomesh

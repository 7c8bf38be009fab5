#pragma once
// Contour discretization by metric length: boundary points spaced at metric length 1
// along every curve (integrating |Mt(c(t)) c'(t)| adaptively), giving the boundary
// loops the planar mesher takes.
#include <cstdint>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/geometry/boundary_loop.h"
#include "anisomesh/geometry/domain.h"

namespace anisomesh {

struct DiscretizeOptions {
  int minSegmentsClosedCurve = 3;       // a contour made of a single curve gets at least this many segments
  std::int64_t maxSegments = 10000000;  // ElementBudgetExceeded above this many boundary segments in total
  double tolerance = 1e-8;              // relative tolerance of the metric length quadrature
  // Absolute tolerance (metric length) of each bisection step: the quadrature stops refining
  // where the step's error estimate is below it even if not below the relative one. The
  // control space's interpolation has kinks at its cell edges, which the relative test alone
  // chased down to 1e-8 metric units (~19 leaves per boundary segment on p2); points are
  // placed by inverting the same estimates, so a segment's length is off by at most the
  // tolerances of its own leaves (~1e-5 for ~10 leaves), not by a sum over the curve.
  double absoluteTolerance = 1e-6;
  bool refineCrossings = true;   // refine curves whose chords cross (coarse metric near close curves)
  int maxRefinementRounds = 10;  // then SelfIntersectingContour
};

// Metric length of c between parameters a and b: the integral of |Mt(c(t)) c'(t)| dt.
double metricLength(const Curve& c, const ControlSpace& cs, double a = 0.0, double b = 1.0, double tolerance = 1e-8);

// Parameters 0 = t_0 < ... < t_n = 1 splitting c into segments of equal metric length
// (per smooth piece: corners of polylines are kept), n_piece = max(1, round(L_M)),
// the whole curve having at least minSegments segments.
std::vector<double> discretizeCurve(const Curve& c, const ControlSpace& cs, int minSegments = 1,
                                    const DiscretizeOptions& options = {});

// Boundary loops of several faces; a curve used by several faces (same CurvePtr) is
// discretized once so the faces share its points. Per face: loops[0] is the outer
// contour (counter-clockwise), then the holes (clockwise); edge refs are curve refs.
// Where chords of different curves (or parts of one) cross, the curves involved get
// twice the segments until no crossing is left (the domain itself must be valid).
std::vector<std::vector<BoundaryLoop>> discretizeDomains(const std::vector<const Domain*>& faces,
                                                         const ControlSpace& cs, const DiscretizeOptions& options = {});

// Boundary loops of one domain (see discretizeDomains).
std::vector<BoundaryLoop> discretizeDomain(const Domain& domain, const ControlSpace& cs,
                                           const DiscretizeOptions& options = {});

}  // namespace anisomesh

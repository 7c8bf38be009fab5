#pragma once
// Section 3.2 checks after contour discretization and the boundary-only triangulation of
// a planar domain: (a) boundary segment lengths (eps1 refinement with the segment's length
// as the reference size; segments outside [1/2, 2] make their contour invalid), (b) chord
// deviation from curved contours (curvature sources, contour invalid), (c) proximity of
// boundaries (thin boundary triangles of metric area below eps2).
#include <array>
#include <vector>

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/controlspace/metric_sources.h"
#include "anisomesh/geometry/domain.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"

namespace anisomesh {

// Thresholds of section 3.2, the paper's values as defaults.
struct BoundaryUpdateOptions {
  double eps1 = 0.8;       // segments shorter (metric) update the control space near them
  double lengthMin = 0.5;  // segments outside [lengthMin, lengthMax] make the contour invalid
  double lengthMax = 2.0;
  double chordTolerance = 0.05;  // largest chord deviation from a curved contour / chord length
  double chordDistance = 0.0;    // largest chord deviation, absolute (MMG's -hausd; 0: off)
  double dMax = 4.0;             // curvature sources: size across the contour = dMax * size along
  // Boundary triangles with metric area below eps2 times the unit equilateral triangle's
  // (sqrt3/4) joining non-adjacent boundary points refine the structure across the gap.
  double eps2 = 0.2;
  double gapElements = 2.0;  // elements wanted across a gap
  int maxRounds = 8;         // bound on the loop (the report says whether it converged)
  bool enabled = true;
};

// Metric length of the straight segment pq (Simpson's rule on |Mt(x) (q - p)|).
double segmentMetricLength(const ControlSpace& cs, const Vec2& p, const Vec2& q);

// A boundary segment of metric length below eps1.
struct ShortSegment {
  Vec2 p, q;
  double length;  // metric length
  int contour;    // index of its loop (0: outer contour, then the holes)
};

// Section 3.2 (a) on the current discretization, every segment measured in cs.
struct SegmentLengthCheck {
  std::vector<ShortSegment> shortSegments;  // metric length < eps1
  std::vector<char> invalidContours;        // per loop: a segment outside [lengthMin, lengthMax]
  int invalidSegments = 0;
};
SegmentLengthCheck checkSegmentLengths(const std::vector<BoundaryLoop>& loops, const ControlSpace& cs,
                                       const BoundaryUpdateOptions& options);

// Section 3.2 (a) update "using the length of this segment as a reference": a segment
// source along each short segment (radius = its length) with the metric at its middle
// scaled so that the segment has metric length 1 there (sizes times its metric length).
// Segments whose source would be undone by the lower size clamp hmin (the update cannot
// lengthen them by 5%) are skipped, so the loop ends. Returns the number added.
int shortSegmentSources(const std::vector<ShortSegment>& segments, const ControlSpace& cs, double hmin,
                        std::vector<MetricSource>* out);

// Section 3.2 (a), structure part: refines the elements larger than a short segment that
// touch it, so the structure resolves the metric there; new nodes take the analytic
// metric (when any) intersected with the interpolated one. Returns the elements added.
int refineNearSegments(AdaptiveControlSpace& cs, const std::vector<ShortSegment>& segments,
                       const MetricFunction& analytic);

// Largest distance of c([a, b]) from its chord, by sampling.
double chordDeviation(const Curve& c, double a, double b);

// Section 3.2 (b): curvature sources (h1 along the contour from the curvature radius R,
// h1 = 0.75 * 8 R chordTolerance, or 0.75 sqrt(8 R chordDistance) when smaller; h2 = dMax h1
// across it) along the chords of curved contours deviating from the curve by more than
// chordTolerance * chord or chordDistance (when > 0), the contour
// marked in invalidContours (when given, sized to the contour count). Returns the largest
// relative deviation.
double chordSources(const Domain& domain, const ControlSpace& cs, const BoundaryUpdateOptions& options,
                    std::vector<MetricSource>* out, std::vector<char>* invalidContours = nullptr);

// Section 3.2 (c): a radial source (size: the triangle's width / gapElements) over each
// triangle of the boundary-only triangulation that joins non-adjacent boundary segments
// and has metric area below eps2 * sqrt(3)/4. Returns the number added.
int proximitySources(const std::vector<BoundaryLoop>& loops, const Mesh& boundaryMesh, const ControlSpace& cs,
                     const BoundaryUpdateOptions& options, std::vector<MetricSource>* out);

// The loops of the next round: fresh (discretized in the updated control space) for the
// contours marked invalid, kept for the others; a kept loop whose segments cross another
// loop is replaced by its fresh one too. Returns per loop whether it is fresh.
std::vector<char> keepValidContours(std::vector<BoundaryLoop>& loops, const std::vector<BoundaryLoop>& fresh,
                                    const std::vector<char>& invalidContours);

}  // namespace anisomesh

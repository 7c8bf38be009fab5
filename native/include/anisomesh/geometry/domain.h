#pragma once
// A planar domain: an outer contour and holes, each a closed chain of curves, and its
// validation (closed chains, no zero-length curve, no crossings, holes strictly inside
// the outer contour and disjoint).
#include <string>
#include <vector>

#include "anisomesh/geometry/curve.h"

namespace anisomesh {

// One curve of a contour, possibly traversed backwards (so faces can share a curve).
struct CurveUse {
  CurvePtr curve;
  bool reversed = false;
  Vec2 start() const { return reversed ? curve->end() : curve->start(); }
  Vec2 end() const { return reversed ? curve->start() : curve->end(); }
};

// A closed chain: the end of curves[i] is the start of curves[i + 1], cyclically.
struct Contour {
  std::vector<CurveUse> curves;
  // Appends a curve traversed forwards (or backwards).
  void add(CurvePtr c, bool reversed = false) { curves.push_back({std::move(c), reversed}); }
};

struct Domain {
  Contour outer;
  std::vector<Contour> holes;
};

struct DomainValidationOptions {
  // Chain ends must meet within closeTolerance * (domain bounding-box diagonal).
  double closeTolerance = 1e-7;
  // Curves shorter than zeroLengthTolerance * diagonal are zero-length.
  double zeroLengthTolerance = 1e-10;
  // Segments per curve piece of the polyline approximation used for the crossing tests.
  int samplesPerCurve = 64;
};

// "outer contour" or "hole 2" (0-based), the prefix of validation messages.
std::string contourName(int contourIndex);

// Bounding box of the domain's curves (sampled, so it covers arcs and splines).
Box2 domainBounds(const Domain& domain);

// Fine polyline approximation of a contour (closed: last point is not repeated).
std::vector<Vec2> sampleContour(const Contour& contour, int samplesPerCurve = 64);

// Signed area of a closed polygon (positive when counter-clockwise).
double signedArea(const std::vector<Vec2>& polygon);

// True when p is strictly inside the closed polygon (even-odd rule).
bool pointInPolygon(const std::vector<Vec2>& polygon, const Vec2& p);

// Where two segments of closed polygons meet (segment i of a polygon joins points i and i + 1).
struct PolygonCrossing {
  int polygonA, segmentA, polygonB, segmentB;
  Vec2 where;
};

// Finds a crossing or touching between non-adjacent segments (or adjacent ones folding
// back) of the closed polygons, using a uniform grid; false when there is none.
bool findPolygonCrossing(const std::vector<std::vector<Vec2>>& polygons, PolygonCrossing* out);

// Throws Error with OpenContour, ZeroLengthCurve, SelfIntersectingContour or
// HoleOutsideDomain (message names the contour, the curve index and the place).
void validateDomain(const Domain& domain, const DomainValidationOptions& options = {});

}  // namespace anisomesh

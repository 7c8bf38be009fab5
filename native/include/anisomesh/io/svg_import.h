#pragma once
// Planar domains from SVG drawings: the closed shapes of an SVG document become a case's
// outer contour and holes (examples/CASE_FORMAT.md "domain"), scaled to a chosen size.
#include <string>

#include <nlohmann/json.hpp>

namespace anisomesh {

struct SvgImportOptions {
  double size = 1.0;  // the larger side of the domain's bounding box after scaling (> 0)
  bool flipY = true;  // SVG's y axis points down: flip it so the drawing stays upright
  // A subpath without Z is closed when its ends meet within this fraction of the drawing's size.
  double closeTolerance = 1e-6;
};

// Reads <path d>, <polygon>, <rect> (rounded corners too), <circle> and <ellipse> elements
// (path commands M, L, H, V, C, S, Q, T, A, Z, absolute and relative), in the document's
// coordinates: the transform attributes of the shapes and of their enclosing <g>, <a> and
// <svg> elements are applied (matrix, translate, scale, rotate, skewX, skewY). Every closed
// subpath is a contour: lines stay lines, quadratic and cubic Beziers become cubic
// "bezier" curves, elliptical arcs cubic Beziers of at most 90 degrees each. Nesting gives
// holes: the one outermost contour is "outer", the contours directly inside it are holes.
// The drawing is translated to start at (0, 0) and scaled so its larger side is options.size.
// Errors: ParseError (malformed path data, numbers or transforms, naming the element and the place),
// OpenContour (a subpath that is not closed), InvalidDomain (no closed shape, several
// outermost contours, or a contour inside a hole).
nlohmann::json domainJsonFromSvg(const std::string& svgText, const SvgImportOptions& options = {});

}  // namespace anisomesh

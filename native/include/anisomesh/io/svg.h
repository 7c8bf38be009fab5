#pragma once
// SVG pictures of meshes, for READMEs and quick looks: planar meshes (or a surface mesh's
// parameter plane) drawn flat; surface meshes (dimension 3) in an orthographic 3D view.
#include <string>
#include <vector>

#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

struct SvgOptions {
  int width = 800;                    // picture width in pixels; the height follows the aspect ratio
  double strokeWidth = 0.6;           // element edge width in pixels
  std::vector<double> elementValues;  // optional per-element value in [0, 1] (e.g. quality) to colour elements
  bool drawBoundary = true;           // boundary edges drawn thicker
  // 3D view: mesh.points projected orthographically, seen from the direction at azimuth
  // (around z, from +x) and elevation (above the xy plane), radians; elements painted
  // back to front (painter's order by mean depth) and shaded by their normal (two-sided).
  bool view3d = false;
  double azimuth = -1.1;
  double elevation = 0.6;
  // Polylines drawn over the mesh (closed), e.g. control-space glyphs: 3D points in the
  // 3D view, else (x, y) of the plane drawn. Not occluded by the mesh.
  std::vector<std::vector<Vec3>> overlay;
};

// Writes the mesh as a standalone SVG document: flat (params if present, else points'
// x, y) or, with view3d, the 3D view of mesh.points.
std::string writeSvg(const Mesh& mesh, const SvgOptions& options = {});

}  // namespace anisomesh

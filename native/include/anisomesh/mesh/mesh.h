#pragma once
// The mesh the pipeline produces: vertices (2D, or 3D on surfaces with their
// parameter coordinates), boundary edges, triangles and quadrilaterals, each with a
// Medit-style integer reference.
#include <array>
#include <vector>

#include "anisomesh/core/types.h"

namespace anisomesh {

struct Mesh {
  int dimension = 2;         // 2: planar, 3: surface
  std::vector<Vec3> points;  // z = 0 for planar meshes
  std::vector<Vec2> params;  // parameter coordinates (planar: x, y); may be empty
  std::vector<int> pointRefs;
  std::vector<std::array<int, 2>> edges;  // boundary edges
  std::vector<int> edgeRefs;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise in the parameter plane
  std::vector<int> triangleRefs;
  std::vector<std::array<int, 4>> quads;  // counter-clockwise in the parameter plane
  std::vector<int> quadRefs;

  int vertexCount() const { return static_cast<int>(points.size()); }
  int elementCount() const { return static_cast<int>(triangles.size() + quads.size()); }
};

}  // namespace anisomesh

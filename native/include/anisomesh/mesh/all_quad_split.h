#pragma once
// The all-quad split of planar and surface meshes: each triangle into 3 quads, each quad
// into 4, one new point per edge (shared by the edge's two elements) and one per element.
#include <array>
#include <vector>

#include "anisomesh/core/types.h"
#include "anisomesh/geometry/boundary_loop.h"
#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

// A boundary edge (mesh vertex indices) and the point that splits it (on its curve).
struct EdgeMidpoint {
  std::array<int, 2> edge;
  Vec2 point;
};

// The midpoints of every loop edge for a mesh whose first vertices are the loops' points in
// order (as the planar mesher numbers them): edge (base + i, base + (i + 1) % n), at
// loop.edgeMidpoints[i] or, when the loop has none, at the straight midpoint.
std::vector<EdgeMidpoint> loopEdgeMidpoints(const std::vector<BoundaryLoop>& loops);

// Splits every element of mesh (in its params, z = 0 for new points) into quads. The given
// boundary edges get their midpoints first, in the given order; any other edge is split at its
// straight midpoint, an element at its centroid. mesh.edges are split in two where a midpoint
// was given. Returns, for each new point in order, the boundary edge it splits ({-1, -1} else).
std::vector<std::array<int, 2>> splitIntoAllQuads(Mesh& mesh, const std::vector<EdgeMidpoint>& boundary);

}  // namespace anisomesh

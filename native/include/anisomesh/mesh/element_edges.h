#pragma once
// The edges of a mesh's elements, each with the elements that own it: one bucketing of
// the element edges serves the quality report's edge lengths and its neighbour size ratio.
#include <array>
#include <vector>

#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

struct ElementEdges {
  std::vector<std::array<int, 2>> edges;  // distinct element edges (a < b), sorted
  // Owners of edges[k]: owners[ownerStart[k] .. ownerStart[k + 1]), in element order
  // (triangles, then quads numbered after them); empty when an element has a negative index.
  std::vector<int> ownerStart;
  std::vector<int> owners;
};

// The distinct edges of all triangles and quads and their owners, in linear time.
ElementEdges elementEdges(const Mesh& mesh);

// Largest ratio of sqrt(area) (in params, or xy) between an edge's first owner and each
// other owner; 1 without shared edges (or owners).
double largestNeighbourSizeRatio(const Mesh& mesh, const ElementEdges& edges);

}  // namespace anisomesh

#pragma once
// Pipeline-level mesh figures next to the mesher's QualityReport: the size ratio of
// neighbouring elements (the quantity gradation bounds), per-element quality for
// pictures.
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/pipeline/pipeline.h"

namespace anisomesh {

// Largest ratio of sqrt(area) (physical) between the two elements sharing an interior
// edge; 1 for a mesh without interior edges.
double largestNeighbourSizeRatio(const Mesh& mesh);

// Metric quality of every element (triangles, then quads) in [0, 1]: triangles
// 4 sqrt3 A_M / sum l_M^2 with Mt averaged over the vertices; quads the smaller of the
// two triangles of their shorter diagonal. Inverted elements get 0.
std::vector<double> elementQualities(const Mesh& mesh, const ControlSpace& cs);

}  // namespace anisomesh

#pragma once
// Sizes for remeshing without a solution file (MMG's -hmin/-hmax alone, -hsiz): an
// isotropic metric per vertex taken from the input mesh itself.
#include <vector>

#include "anisomesh/mesh/mesh.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

// Per vertex: the isotropic metric of the mean length of the vertex's incident edges
// (element and boundary edges, each once); InvalidArgument for a vertex on no edge.
std::vector<Metric> edgeLengthMetrics(const Mesh& mesh);

// Per vertex: the isotropic metric of size h (InvalidMetric unless h > 0 and finite).
std::vector<Metric> uniformMetrics(const Mesh& mesh, double h);

}  // namespace anisomesh

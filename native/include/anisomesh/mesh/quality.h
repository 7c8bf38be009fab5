#pragma once
// Quality of a mesh measured in the metric of a control space: edge metric lengths
// (target 1), element shape quality in metric space, inverted/degenerate counts, and
// the mesher's stage timings.
#include <array>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"

namespace anisomesh {

struct QualityReport {
  int vertices = 0;
  int triangles = 0;
  int quads = 0;
  int edges = 0;  // distinct element edges
  // Edge metric length, Mt averaged over the two end points.
  double edgeLengthMin = 0.0;
  double edgeLengthMean = 0.0;
  double edgeLengthMax = 0.0;
  double edgesWithinSqrt2 = 0.0;  // fraction of edges with length in [1/sqrt2, sqrt2]
  double edgesWithin06_13 = 0.0;  // fraction of edges with length in [0.6, 1.3]
  // Element quality in metric space (Mt averaged over the element's vertices):
  // triangles Q = 4 sqrt(3) A_M / sum l_M^2; quads min over corners of 2|e1 x e2| / (|e1|^2 + |e2|^2).
  // Both are 1 for the ideal element (equilateral / square in metric space).
  double qualityMin = 0.0;
  double qualityMean = 0.0;
  double triangleQualityMin = 0.0;
  double triangleQualityMean = 0.0;
  double quadQualityMin = 0.0;
  double quadQualityMean = 0.0;
  std::array<int, 10> qualityHistogram{};  // element counts per quality bin [k/10, (k+1)/10); <= 0 in bin 0
  int inverted = 0;                        // clockwise (or, for quads, with a reflex corner) in the parameter plane
  int degenerate = 0;                      // not inverted but flat: zero area or metric quality below 1e-3
  double largestNeighbourSizeRatio = 1.0;  // of sqrt(area) across shared edges (element_edges.h)
  MesherTimings timings;                   // filled by the caller from PlanarMesherOptions::timings
};

// The distinct edges of all triangles and quads (a < b), sorted.
std::vector<std::array<int, 2>> distinctElementEdges(const Mesh& mesh);

// What the report summarizes, item by item (for colouring and histograms).
struct ElementMeasures {
  std::vector<std::array<int, 2>> edges;  // distinct element edges (a < b), sorted
  std::vector<double> edgeLength;         // metric length of each edge
  std::vector<double> quality;            // metric quality of each triangle, then each quad
  std::vector<double> vertexMinSize;      // smallest requested size at each vertex
};

// Measures mesh in the metric of controlSpace (queried once per vertex at its params, or
// xy); with perItem, also keeps the per-edge, per-element and per-vertex values.
QualityReport measureQuality(const Mesh& mesh, const ControlSpace& controlSpace, ElementMeasures* perItem = nullptr);

// Metric area of every triangle (det of the vertex-averaged Mt times the area), in the
// order of mesh.triangles: the paper's boundary-proximity check (section 3.2) flags
// triangles of the boundary-only triangulation below eps2 = 0.2.
std::vector<double> triangleMetricAreas(const Mesh& mesh, const ControlSpace& controlSpace);

}  // namespace anisomesh

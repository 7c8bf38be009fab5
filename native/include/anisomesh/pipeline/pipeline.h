#pragma once
// End-to-end runs: a JSON case (validate domain -> control space -> contour
// discretization -> planar mesher) and remeshing of a Medit mesh under a .sol metric.
#include <string>
#include <vector>

#include "anisomesh/io/case_json.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"

namespace anisomesh {

// What a run did, for --stats and logs.
struct PipelineReport {
  int boundaryLoops = 0;
  int boundaryPoints = 0;
  double secondsGeometry = 0.0;   // validation + discretization
  double secondsMeshing = 0.0;    // meshPlanarBoundary
  std::vector<std::string> notes; // e.g. options accepted but not applied yet
};

// The mesher options of a case (quads, allQuads, maxElements).
PlanarMesherOptions mesherOptionsFromCase(const CaseSpec& spec);

// Meshes a case: validateDomain, buildCaseControlSpace, discretizeDomain, meshPlanarBoundary.
Mesh meshCase(const CaseSpec& spec, PipelineReport* report = nullptr);

struct RemeshOptions {
  double hmin = 0.0;   // clamp every requested size to >= hmin (0: off)
  double hmax = 0.0;   // clamp every requested size to <= hmax (0: off)
  double hgrad = 0.0;  // size gradation: accepted but NOT applied yet (noted in the report)
  PlanarMesherOptions mesher;
};

// Remeshes the domain bounded by the input mesh's boundary loops under the per-vertex
// metrics (piecewise linear over the input triangles); boundary refs are kept.
Mesh remesh(const Mesh& input, const std::vector<Metric>& metrics, const RemeshOptions& options = {},
            PipelineReport* report = nullptr);

}  // namespace anisomesh

#pragma once
// The reports as JSON (stable key names, for the CLI, the WebAssembly package and the
// web front end): the mesh quality report, the planar pipeline's --stats object and the
// surface meshing report.
#include <nlohmann/json.hpp>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {

// The quality report as JSON.
nlohmann::json qualityReportToJson(const QualityReport& report);

// qualityReportToJson(measureQuality(mesh, cs)) merged with the pipeline report (stage
// times, counts, section 3.2 rounds) and largestNeighbourSizeRatio.
nlohmann::json pipelineStatsJson(const Mesh& mesh, const ControlSpace& cs, const PipelineReport& report);

// The surface meshing report as JSON.
nlohmann::json surfaceMeshReportToJson(const SurfaceMeshReport& report);

}  // namespace anisomesh

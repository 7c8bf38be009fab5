#pragma once
// One entry point for a whole JSON case run (parse -> mesh -> measure), shared by the
// CLI and the WebAssembly bindings so both give the same mesh and the same report.
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/pipeline/pipeline.h"

namespace anisomesh {

struct RunCaseOptions {
  bool inspectControlSpace = false;  // also export the control space (nodes, cells) as JSON
  int sampleGrid = 32;               // grid used to sample a control space without nodes
};

// Everything a case run produces.
struct CaseRun {
  Mesh mesh;
  QualityReport quality;
  PipelineReport pipeline;
  nlohmann::json controlSpace;  // null unless RunCaseOptions::inspectControlSpace
};

// Parses the JSON case text, meshes it and measures the mesh in the case's metric.
CaseRun runCase(const std::string& jsonText, const RunCaseOptions& options = {});

// The --stats object of a run: the quality report plus the pipeline's counts and times.
nlohmann::json caseRunStatsJson(const CaseRun& run);

}  // namespace anisomesh

#include "anisomesh/pipeline/run_case.h"

#include "anisomesh/io/case_json.h"
#include "anisomesh/io/control_space_export.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/surface_case_json.h"

namespace anisomesh {

bool isSurfaceCase(const std::string& jsonText) { return isSurfaceCaseJson(jsonText); }

CaseRun runCase(const std::string& jsonText, const RunCaseOptions& options) {
  CaseRun run;
  if (isSurfaceCaseJson(jsonText)) {
    SurfaceCaseSpec spec = parseSurfaceCaseJson(jsonText);
    if (options.maxElements > 0) spec.options.mesher.maxElements = options.maxElements;
    if (options.progress) spec.options.mesher.progress = options.progress;
    SurfaceMeshReport report;
    run.mesh = meshSurfaceCase(spec, &report);
    run.stats = surfaceMeshReportToJson(report);
    return run;
  }
  CaseSpec spec = parseCaseJson(jsonText);
  if (options.quads) spec.options.quads = *options.quads;
  if (options.allQuads) spec.options.allQuads = *options.allQuads;
  if (options.maxElements > 0) spec.options.maxElements = options.maxElements;
  BoundaryUpdateOptions updates;
  updates.enabled = options.controlSpaceUpdates;
  PipelineReport report;
  run.mesh = meshCase(spec, &report, updates, &run.finalSpace, options.progress);
  run.stats = pipelineStatsJson(run.mesh, *run.finalSpace, report);
  if (options.inspectControlSpace) run.controlSpace = controlSpaceToJson(*run.finalSpace);
  return run;
}

}  // namespace anisomesh

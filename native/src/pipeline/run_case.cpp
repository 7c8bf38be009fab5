#include "anisomesh/pipeline/run_case.h"

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/control_space_export.h"
#include "anisomesh/pipeline/case_control_space.h"

namespace anisomesh {

CaseRun runCase(const std::string& jsonText, const RunCaseOptions& options) {
  const CaseSpec spec = parseCaseJson(jsonText);
  CaseRun run;
  run.mesh = meshCase(spec, &run.pipeline);
  // The mesher's own control space is internal to meshCase: rebuild it (deterministic)
  // to measure the mesh and to export it.
  const std::unique_ptr<ControlSpace> cs = buildCaseControlSpace(spec);
  run.quality = measureQuality(run.mesh, *cs);
  if (options.inspectControlSpace) {
    if (const auto* adaptive = dynamic_cast<const AdaptiveControlSpace*>(cs.get()))
      run.controlSpace = controlSpaceToJson(*adaptive);
    else
      run.controlSpace = sampledControlSpaceToJson(*cs, options.sampleGrid, options.sampleGrid);
  }
  return run;
}

nlohmann::json caseRunStatsJson(const CaseRun& run) {
  nlohmann::json j = qualityReportToJson(run.quality);
  j["boundaryLoops"] = run.pipeline.boundaryLoops;
  j["boundaryPoints"] = run.pipeline.boundaryPoints;
  j["secondsGeometry"] = run.pipeline.secondsGeometry;
  j["secondsMeshing"] = run.pipeline.secondsMeshing;
  j["notes"] = run.pipeline.notes;
  return j;
}

}  // namespace anisomesh

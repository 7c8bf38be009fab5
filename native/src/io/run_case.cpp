#include "anisomesh/io/run_case.h"

#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/control_space_export.h"
#include "anisomesh/io/json_syntax.h"
#include "anisomesh/io/json_text.h"
#include "anisomesh/io/report_json.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/patch_params.h"
#include "json_reader.h"

namespace anisomesh {

bool isSurfaceCase(const std::string& jsonText) { return isSurfaceCaseJson(jsonText); }

Mesh meshSurfaceCase(const std::string& jsonText, SurfaceMeshReport* report) {
  return meshSurfaceCase(parseSurfaceCaseJson(jsonText), report);
}

namespace {

// Reads a case with a reader that may let nlohmann's own exceptions escape (a number
// overflowing a double is out_of_range 406): every one of them becomes a ParseError.
template <class F>
auto readCase(const std::string& jsonText, F&& read) -> decltype(read()) {
  try {
    return withStage("reading the case", read);
  } catch (const nlohmann::json::exception& e) {
    if (e.id == 406) requireNoJsonNumberOverflow(jsonText);  // names the path
    throw Error(ErrorCode::ParseError, std::string("malformed JSON: ") + e.what());
  }
}

// The --stats object of a surface run: the mesher's report with the keys every report has
// (planar reports carry the same), measured in 3D here.
nlohmann::json surfaceRunStats(const Mesh& mesh, const SurfaceMeshReport& report) {
  nlohmann::json stats = surfaceMeshReportToJson(report);
  const nlohmann::json& q = stats["quality3d"];
  stats["quads"] = mesh.quads.size();
  stats["inverted"] = q["inverted"];
  stats["edgeLength"] = {{"min", q["edgeLengthMin"]},
                         {"mean", q["edgeLengthMean"]},
                         {"max", q["edgeLengthMax"]},
                         {"fractionWithinSqrt2", q["edgesWithinSqrt2"]}};
  stats["quality"] = {{"mean", q["qualityMean"]}, {"min", q["qualityMin"]}};
  return stats;
}

CaseRun runCaseUnguarded(const std::string& jsonText, const RunCaseOptions& options) {
  // Parsed once (a 1M-point polyline is 33 MB of text); on a syntax error the check
  // below gives one clean message for both kinds of case.
  nlohmann::json root = readCase(jsonText, [&] {
    requireNoNulByte(jsonText);
    nlohmann::json parsed = nlohmann::json::parse(jsonText, nullptr, false);
    if (parsed.is_discarded()) {
      checkJsonSyntax(jsonText);  // throws (an overflowing number: out_of_range 406)
      throw Error(ErrorCode::ParseError, "(root): malformed JSON");
    }
    return parsed;
  });
  CaseRun run;
  if (isSurfaceCaseJsonTree(root)) {
    SurfaceCaseSpec spec = readCase(jsonText, [&] { return parseSurfaceCaseJsonTree(root); });
    root = nullptr;  // the tree is not needed while meshing
    if (options.maxElements > 0) spec.options.mesher.maxElements = options.maxElements;
    if (options.maxControlNodes > 0) spec.options.maxControlNodes = options.maxControlNodes;
    if (options.progress) spec.options.mesher.progress = options.progress;
    if (options.quads) spec.options.quads = *options.quads;
    if (options.allQuads) spec.options.allQuads = *options.allQuads;
    spec.options.controlSpaceGlyphs = options.controlSpaceGlyphs;
    spec.options.deferQuality = !options.stats;
    auto report = std::make_shared<SurfaceMeshReport>();
    run.mesh = withStage("surface meshing", [&] { return meshSurfaceCase(spec, report.get()); });
    if (!options.stats && options.elementMeasures) measureSurfaceElements(*report);
    run.elementQuality = std::move(report->elementQuality);
    run.edgeLengths = std::move(report->edgeLengths);
    run.glyphs = std::move(report->controlSpaceGlyphs);
    if (options.patchParams) {
      run.elementPatch = elementPatches(spec.model, run.mesh);
      run.cornerParams = patchCornerParams(spec.model, run.mesh);
    }
    if (options.stats)
      run.stats = surfaceRunStats(run.mesh, *report);
    else
      run.surfaceReport = std::move(report);
    return run;
  }
  CaseSpec spec = readCase(jsonText, [&] { return parseCaseJsonTree(root); });
  root = nullptr;
  if (options.quads) spec.options.quads = *options.quads;
  if (options.allQuads) spec.options.allQuads = *options.allQuads;
  if (options.maxElements > 0) spec.options.maxElements = options.maxElements;
  if (options.maxControlNodes > 0) spec.options.maxControlNodes = options.maxControlNodes;
  BoundaryUpdateOptions updates = spec.boundary;
  updates.enabled = options.controlSpaceUpdates;
  run.mesh = meshCase(spec, &run.report, updates, &run.finalSpace, options.progress);
  if (options.stats)
    run.stats = withStage("quality report", [&] { return pipelineStatsJson(run.mesh, *run.finalSpace, run.report); });
  if (options.inspectControlSpace) run.controlSpace = controlSpaceToJson(*run.finalSpace);
  if (options.vertexMetrics) {
    // The metric the mesh was built for, so colourings match the report exactly.
    run.vertexMetrics.reserve(3 * run.mesh.points.size());
    for (size_t i = 0; i < run.mesh.points.size(); ++i) {
      const Vec2 p =
          run.mesh.params.size() == run.mesh.points.size() ? run.mesh.params[i] : Vec2(run.mesh.points[i].head<2>());
      const Mat2 m = run.finalSpace->metricAt(p).tensor();
      run.vertexMetrics.insert(run.vertexMetrics.end(), {m(0, 0), m(0, 1), m(1, 1)});
    }
  }
  return run;
}

}  // namespace

CaseRun runCase(const std::string& jsonText, const RunCaseOptions& options) {
  return withStage("the case run", [&] { return runCaseUnguarded(jsonText, options); });
}

nlohmann::json caseRunStats(const CaseRun& run) {
  if (!run.stats.is_null()) return run.stats;
  if (run.surfaceReport) {
    finishSurfaceMeasures(*run.surfaceReport);
    return surfaceRunStats(run.mesh, *run.surfaceReport);
  }
  if (!run.finalSpace) return run.stats;
  return pipelineStatsJson(run.mesh, *run.finalSpace, run.report);
}

}  // namespace anisomesh

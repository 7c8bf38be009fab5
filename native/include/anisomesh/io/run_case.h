#pragma once
// One entry point for a whole JSON case run (parse -> mesh -> measure), shared by the
// CLI and the WebAssembly bindings so both give the same mesh and the same report.
// Planar cases (examples/CASE_FORMAT.md) and surface cases (examples/SURFACE_FORMAT.md,
// recognised by their "patches") go through the same call.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {

struct RunCaseOptions {
  std::optional<bool> quads;          // overrides the case's options.quads
  std::optional<bool> allQuads;       // overrides options.allQuads
  std::int64_t maxElements = -1;      // > 0: overrides options.maxElements
  std::int64_t maxControlNodes = -1;  // planar, > 0: overrides the control-space node budget
  bool controlSpaceUpdates = true;    // planar: the section 3.2 update loop
  bool inspectControlSpace = false;   // also export the final control space (nodes, cells) as JSON
  bool vertexMetrics = false;         // planar: also the final control space's metric at every vertex
  bool controlSpaceGlyphs = false;    // surface: also CaseRun::glyphs (the final control spaces drawn)
  bool patchParams = false;           // surface: also CaseRun::elementPatch and CaseRun::cornerParams
  // false leaves CaseRun::stats null (caseRunStats() makes it later); a surface run then
  // also leaves its 3D measures (chord deviations, ...) to caseRunStats().
  bool stats = true;
  bool elementMeasures = true;  // surface, stats false: CaseRun::elementQuality, edgeLengths all the same
  // Called with a fraction in [0, 1] while meshing; returning false cancels (ErrorCode::Cancelled).
  std::function<bool(double)> progress;
};

// Everything a case run produces.
struct CaseRun {
  Mesh mesh;
  nlohmann::json stats;                              // the --stats object
  nlohmann::json controlSpace;                       // null unless inspectControlSpace
  std::vector<double> vertexMetrics;                 // m11, m12, m22 per vertex (RunCaseOptions::vertexMetrics)
  std::unique_ptr<AdaptiveControlSpace> finalSpace;  // planar: the control space meshed with
  std::vector<double> elementQuality;                // surface: 3D quality per element (triangles, then quads)
  std::vector<SurfaceEdgeLength> edgeLengths;        // surface: 3D metric length of every distinct edge
  std::vector<ControlSpaceGlyph> glyphs;             // surface: with RunCaseOptions::controlSpaceGlyphs
  std::vector<int> elementPatch;                     // surface, patchParams: patch index per element
  std::vector<Vec2> cornerParams;                    // surface, patchParams: (u, v) per element corner in its patch
  PipelineReport report;                             // planar: stage times and section 3.2 counts
  std::shared_ptr<SurfaceMeshReport> surfaceReport;  // surface, stats false: the report caseRunStats() finishes
};

// True when the JSON text is a surface case (it has "patches").
bool isSurfaceCase(const std::string& jsonText);

// Parses a surface case and meshes it (meshSurfaceCase of pipeline.h).
Mesh meshSurfaceCase(const std::string& jsonText, SurfaceMeshReport* report = nullptr);

// Parses the JSON case text, meshes it and measures the mesh in the case's metric. Every
// failure is an Error: ParseError (with the JSON path, number overflow included),
// OutOfMemory naming the stage, or the code of the stage that refused the input.
CaseRun runCase(const std::string& jsonText, const RunCaseOptions& options = {});

// The --stats object of a run made with RunCaseOptions::stats = false (the same object
// runCase would have put in CaseRun::stats; a surface run's 3D measures are made now);
// a run's stats as they are otherwise.
nlohmann::json caseRunStats(const CaseRun& run);

}  // namespace anisomesh

#pragma once
// The JSON surface case format (documented in examples/SURFACE_FORMAT.md): surfaces,
// trimmed patches in (u, v), shared curves, the surface metric options, user sources
// and the adaptation switch, parsed into a SurfaceModel and SurfaceMeshOptions.
#include <string>

#include <nlohmann/json.hpp>

#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {

struct SurfaceCaseSpec {
  SurfaceModel model;
  SurfaceMeshOptions options;
};

// Parses a surface case; throws ParseError naming the JSON path (and, for formulas, the
// column), InvalidArgument / InvalidMetric with the path for values out of range.
SurfaceCaseSpec parseSurfaceCaseJson(const std::string& text);
// Same from JSON parsed once by the caller.
SurfaceCaseSpec parseSurfaceCaseJsonTree(const nlohmann::json& root);

// True when the JSON text is a surface case (has "patches"), to route `anisomesh mesh`.
bool isSurfaceCaseJson(const std::string& text);
// Same for parsed JSON.
bool isSurfaceCaseJsonTree(const nlohmann::json& root);

// Parses and meshes a surface case (meshSurfaceModel).
Mesh meshSurfaceCase(const std::string& jsonText, SurfaceMeshReport* report = nullptr);
// Same from a parsed spec.
Mesh meshSurfaceCase(const SurfaceCaseSpec& spec, SurfaceMeshReport* report = nullptr);

// The report as JSON (stable key names, for the CLI).
nlohmann::json surfaceMeshReportToJson(const SurfaceMeshReport& report);

}  // namespace anisomesh

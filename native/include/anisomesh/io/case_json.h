#pragma once
// The JSON case readers: planar cases (examples/CASE_FORMAT.md) and surface cases
// (examples/SURFACE_FORMAT.md) parsed into the case model (pipeline/case_model.h), every
// field read and every error worded by the same path-aware readers.
#include <string>

#include "anisomesh/pipeline/case_model.h"

namespace anisomesh {

// Parses a JSON case; throws ParseError naming the JSON path (e.g.
// "sources[2].radius: expected a number") on malformed JSON, missing fields, wrong
// types or unknown fields, InvalidArgument / InvalidMetric (with the path) on values out
// of range (non-finite numbers included). The domain is built but not validated (see validateDomain).
CaseSpec parseCaseJson(const std::string& text);

// Reads and parses a case file (IoError when unreadable).
CaseSpec readCaseFile(const std::string& path);

// Parses a surface case; throws ParseError naming the JSON path (and, for formulas, the
// column), InvalidArgument / InvalidMetric with the path for values out of range.
SurfaceCaseSpec parseSurfaceCaseJson(const std::string& text);

// True when the JSON text is a surface case (has "patches"), to route `anisomesh mesh`.
bool isSurfaceCaseJson(const std::string& text);

}  // namespace anisomesh

// The planar case reader (examples/CASE_FORMAT.md); the readers of every field are those
// of json_reader.h, shared with the surface case reader.
#include "anisomesh/io/case_json.h"

#include <cmath>

#include "anisomesh/core/number_text.h"
#include "anisomesh/io/file_io.h"
#include "json_reader.h"

namespace anisomesh {
namespace {

using namespace json_reader;  // NOLINT(google-build-using-namespace): the readers of this file

CaseControlSpaceSpec parseControlSpace(const json& v, const std::string& path) {
  expectObject(v, path);
  checkKeys(v, path,
            {"kind", "hmin", "hmax", "gradation", "interpolation", "refineThreshold", "maxLevel", "queryCache"});
  CaseControlSpaceSpec cs;
  if (v.contains("kind")) {
    cs.kind = string(v["kind"], child(path, "kind"));
    if (cs.kind != "quadtree" && cs.kind != "background")
      fail(child(path, "kind"), "expected \"quadtree\" or \"background\", got \"" + cs.kind + "\"");
  }
  cs.hmax = positiveField(v, path, "hmax");
  if (v.contains("hmin")) {
    cs.hmin = number(v["hmin"], child(path, "hmin"));
    require(cs.hmin >= 0 && cs.hmin <= cs.hmax, ErrorCode::InvalidArgument,
            child(path, "hmin") + ": must be in [0, hmax], got " + std::to_string(cs.hmin));
  }
  if (v.contains("gradation") && !v["gradation"].is_null()) {
    const double dr = number(v["gradation"], child(path, "gradation"));
    require(dr >= 1, ErrorCode::InvalidArgument,
            child(path, "gradation") + ": must be >= 1 or null, got " + std::to_string(dr));
    cs.gradation = dr;
  }
  if (v.contains("refineThreshold"))
    cs.refineThreshold = positive(v["refineThreshold"], child(path, "refineThreshold"));
  if (v.contains("maxLevel")) {
    cs.maxLevel = integer(v["maxLevel"], child(path, "maxLevel"));
    require(cs.maxLevel >= 2 && cs.maxLevel <= 20, ErrorCode::InvalidArgument,
            child(path, "maxLevel") + ": must be in [2, 20], got " + std::to_string(cs.maxLevel));
  }
  if (v.contains("queryCache")) {
    cs.queryCache = number(v["queryCache"], child(path, "queryCache"));
    require(cs.queryCache >= 0, ErrorCode::InvalidArgument,
            child(path, "queryCache") + ": must be >= 0 (0: off), got " + numberText(cs.queryCache));
  }
  if (v.contains("interpolation")) {
    cs.interpolation = string(v["interpolation"], child(path, "interpolation"));
    const bool quadtree = cs.kind == "quadtree";
    const bool ok = cs.interpolation == "bilinear" ||
                    (quadtree ? cs.interpolation == "serendipity"
                              : cs.interpolation == "linear" || cs.interpolation == "inverse_distance");
    if (!ok)
      fail(child(path, "interpolation"),
           std::string(quadtree ? "expected \"bilinear\" or \"serendipity\" for a quadtree"
                                : "expected \"linear\" or \"inverse_distance\" for a background mesh") +
               ", got \"" + cs.interpolation + "\"");
  }
  return cs;
}

CaseOptions parseOptions(const json& v, const std::string& path) {
  expectObject(v, path);
  checkKeys(v, path, {"quads", "allQuads", "maxElements"});
  CaseOptions o;
  if (v.contains("quads")) o.quads = boolean(v["quads"], child(path, "quads"));
  if (v.contains("allQuads")) o.allQuads = boolean(v["allQuads"], child(path, "allQuads"));
  if (v.contains("maxElements")) {
    const json& m = v["maxElements"];
    if (!m.is_number_integer())
      fail(child(path, "maxElements"), std::string("expected an integer, got ") + m.type_name());
    o.maxElements = m.get<std::int64_t>();
    require(o.maxElements > 0, ErrorCode::InvalidArgument, child(path, "maxElements") + ": must be positive");
  }
  return o;
}

}  // namespace

CaseSpec parseCaseJson(const std::string& text) { return parseCaseJsonTree(parseText(text)); }

CaseSpec parseCaseJsonTree(const json& root) {
  expectObject(root, "");
  checkKeys(root, "", {"domain", "controlSpace", "sources", "options", "boundary", "name", "description"});
  CaseSpec spec;
  const json& domain = member(root, "", "domain");
  expectObject(domain, "domain");
  checkKeys(domain, "domain", {"outer", "holes"});
  spec.domain.outer = parseContour(member(domain, "domain", "outer"), "domain.outer", 1);
  if (domain.contains("holes")) {
    const json& holes = array(domain["holes"], "domain.holes", "contours");
    for (size_t i = 0; i < holes.size(); ++i)
      spec.domain.holes.push_back(parseContour(holes[i], index("domain.holes", i), int(i) + 2));
  }
  spec.controlSpace = parseControlSpace(member(root, "", "controlSpace"), "controlSpace");
  if (root.contains("sources")) {
    const json& s = array(root["sources"], "sources", "sources");
    for (size_t i = 0; i < s.size(); ++i)
      spec.sources.push_back(parseSource(s[i], index("sources", i),
                                         {SourceType::Radial, SourceType::Segment, SourceType::Polyline,
                                          SourceType::Curve, SourceType::Nodes, SourceType::Analytic}));
  }
  if (root.contains("options")) spec.options = parseOptions(root["options"], "options");
  if (root.contains("boundary")) spec.boundary = parseBoundaryRules(root["boundary"], "boundary", true);
  return spec;
}

CaseSpec readCaseFile(const std::string& path) {
  try {
    return parseCaseJson(readTextFile(path));
  } catch (const Error& e) {
    if (e.code() == ErrorCode::IoError) throw;
    throw Error(e.code(), path + ": " + e.what());
  }
}

bool isSurfaceCaseJson(const std::string& text) {
  try {
    return isSurfaceCaseJsonTree(json::parse(text));
  } catch (const json::exception&) {
    return false;
  }
}

bool isSurfaceCaseJsonTree(const json& root) { return root.is_object() && root.contains("patches"); }

}  // namespace anisomesh

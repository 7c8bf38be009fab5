#pragma once
// Private to io/: the path-aware JSON readers every case reader uses (planar and surface
// cases), so that every field is checked the same way and every message names its JSON
// path the same way ("sources[2].radius: expected a number, got string").
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/domain.h"
#include "anisomesh/metric/metric.h"
#include "anisomesh/pipeline/case_model.h"

namespace anisomesh {
namespace json_reader {

using json = nlohmann::json;

// Throws ParseError "path: what" ("(root)" for the empty path).
[[noreturn]] void fail(const std::string& path, const std::string& what);
// path.key, and path[i].
std::string child(const std::string& path, const std::string& key);
std::string index(const std::string& path, size_t i);
// Constructor errors get the JSON path in front (unless they already name it).
template <class F>
auto withPath(const std::string& path, F f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error& e) {
    if (std::string(e.what()).rfind(path, 0) == 0) throw;
    throw Error(e.code(), path + ": " + e.what());
  }
}

// The text parsed as JSON (ParseError "(root): malformed JSON: ..." otherwise).
json parseText(const std::string& text);
void expectObject(const json& v, const std::string& path);
// Rejects keys outside the allowed set, so a typo does not silently fall back to a default.
void checkKeys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed);
// obj[key]; ParseError "path.key: missing field" without it.
const json& member(const json& obj, const std::string& path, const char* key);
// An array (ParseError naming what its items should be otherwise).
const json& array(const json& v, const std::string& path, const char* items);

// A finite number (InvalidArgument for a non-finite one).
double number(const json& v, const std::string& path);
// A finite number > 0.
double positive(const json& v, const std::string& path);
bool boolean(const json& v, const std::string& path);
std::string string(const json& v, const std::string& path);
// An integer in the range of int.
int integer(const json& v, const std::string& path);
// A point [x, y] (form names the coordinates in messages, e.g. "[u, v]").
Vec2 point(const json& v, const std::string& path, const char* form = "[x, y]");
Vec3 point3(const json& v, const std::string& path);
// At least minCount points.
std::vector<Vec2> points(const json& v, const std::string& path, size_t minCount, const char* form = "[x, y]");
// [[x0, y0], [x1, y1]] with x1 > x0 and y1 > y0 (InvalidDomain otherwise).
Box2 box(const json& v, const std::string& path);

// obj[key] read by one of the readers above, or def when obj has no key.
inline double numberField(const json& obj, const std::string& path, const char* key) {
  return number(member(obj, path, key), child(path, key));
}
inline double positiveField(const json& obj, const std::string& path, const char* key) {
  return positive(member(obj, path, key), child(path, key));
}
inline Vec2 pointField(const json& obj, const std::string& path, const char* key, const char* form = "[x, y]") {
  return point(member(obj, path, key), child(path, key), form);
}
inline double numberOr(const json& obj, const std::string& path, const char* key, double def) {
  return obj.contains(key) ? number(obj[key], child(path, key)) : def;
}
inline double positiveOr(const json& obj, const std::string& path, const char* key, double def) {
  return obj.contains(key) ? positive(obj[key], child(path, key)) : def;
}

// A curve of CASE_FORMAT.md (line, arc, circle, polyline, bezier, bspline); its reference
// defaults to defaultRef.
CurveUse parseCurve(const json& v, const std::string& path, int defaultRef, const char* form = "[x, y]");
// A non-empty array of curves.
Contour parseContour(const json& v, const std::string& path, int defaultRef, const char* form = "[x, y]");
// {"alpha", "h1", "h2"}: alpha defaults to 0, h2 to h1.
MetricSizes parseMetric(const json& v, const std::string& path);
// "boundary": the section 3.2 thresholds, the paper's values where absent; planar cases
// also take chordTolerance, gapElements and maxRounds (surfaces check chords in 3D against
// metric.chordTolerance and bound their rounds with options.maxRounds).
BoundaryUpdateOptions parseBoundaryRules(const json& v, const std::string& path, bool planar);
// One entry of "sources" (radial, segment, polyline, nodes, analytic), of the types allowed.
SourceSpec parseSource(const json& v, const std::string& path, std::initializer_list<SourceType> allowed);

}  // namespace json_reader

// The case readers from JSON parsed once by the caller (runCase: a 33 MB case is not
// parsed twice); isSurfaceCaseJsonTree: the root has "patches".
CaseSpec parseCaseJsonTree(const nlohmann::json& root);
SurfaceCaseSpec parseSurfaceCaseJsonTree(const nlohmann::json& root);
bool isSurfaceCaseJsonTree(const nlohmann::json& root);

}  // namespace anisomesh

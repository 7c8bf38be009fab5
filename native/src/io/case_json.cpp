#include "anisomesh/io/case_json.h"

#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/expression.h"
#include "anisomesh/io/file_io.h"

namespace anisomesh {
namespace {

using json = nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::ParseError, (path.empty() ? std::string("(root)") : path) + ": " + what);
}

std::string child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string index(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

const char* typeName(const json& v) { return v.type_name(); }

void expectObject(const json& v, const std::string& path) {
  if (!v.is_object()) fail(path, std::string("expected an object, got ") + typeName(v));
}

// Rejects keys outside the allowed set, so a typo does not silently fall back to a default.
void checkKeys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail(child(path, it.key()), "unknown field (expected one of: " + list + ")");
    }
  }
}

const json& member(const json& obj, const std::string& path, const char* key) {
  auto it = obj.find(key);
  if (it == obj.end()) fail(child(path, key), "missing field");
  return *it;
}

double number(const json& v, const std::string& path) {
  if (!v.is_number()) fail(path, std::string("expected a number, got ") + typeName(v));
  return v.get<double>();
}

double positive(const json& v, const std::string& path) {
  const double x = number(v, path);
  require(x > 0 && std::isfinite(x), ErrorCode::InvalidArgument, path + ": must be positive, got " + std::to_string(x));
  return x;
}

double numberField(const json& obj, const std::string& path, const char* key) {
  return number(member(obj, path, key), child(path, key));
}
double positiveField(const json& obj, const std::string& path, const char* key) {
  return positive(member(obj, path, key), child(path, key));
}

Vec2 point(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    fail(path, std::string("expected a point [x, y], got ") +
                   (v.is_array() ? "an array of " + std::to_string(v.size()) : typeName(v)));
  return {v[0].get<double>(), v[1].get<double>()};
}
Vec2 pointField(const json& obj, const std::string& path, const char* key) {
  return point(member(obj, path, key), child(path, key));
}

std::vector<Vec2> points(const json& v, const std::string& path, size_t minCount) {
  if (!v.is_array()) fail(path, std::string("expected an array of points, got ") + typeName(v));
  if (v.size() < minCount)
    fail(path, "expected at least " + std::to_string(minCount) + " points, got " + std::to_string(v.size()));
  std::vector<Vec2> out;
  for (size_t i = 0; i < v.size(); ++i) out.push_back(point(v[i], index(path, i)));
  return out;
}

bool boolean(const json& v, const std::string& path) {
  if (!v.is_boolean()) fail(path, std::string("expected true or false, got ") + typeName(v));
  return v.get<bool>();
}

std::string string(const json& v, const std::string& path) {
  if (!v.is_string()) fail(path, std::string("expected a string, got ") + typeName(v));
  return v.get<std::string>();
}

int integer(const json& v, const std::string& path) {
  if (!v.is_number_integer()) fail(path, std::string("expected an integer, got ") + typeName(v));
  const auto x = v.get<long long>();
  if (x < -2147483647LL || x > 2147483647LL) fail(path, "integer out of range");
  return int(x);
}

// A curve; its reference defaults to defaultRef.
CurveUse parseCurve(const json& v, const std::string& path, int defaultRef) {
  expectObject(v, path);
  const std::string type = string(member(v, path, "type"), child(path, "type"));
  const int ref = v.contains("ref") ? integer(v["ref"], child(path, "ref")) : defaultRef;
  const bool reversed = v.contains("reversed") && boolean(v["reversed"], child(path, "reversed"));
  CurvePtr c;
  try {
    if (type == "line") {
      checkKeys(v, path, {"type", "ref", "reversed", "p1", "p2"});
      c = std::make_shared<LineCurve>(pointField(v, path, "p1"), pointField(v, path, "p2"), ref);
    } else if (type == "arc") {
      if (v.contains("points")) {
        checkKeys(v, path, {"type", "ref", "reversed", "points"});
        const auto p = points(v["points"], child(path, "points"), 3);
        if (p.size() != 3)
          fail(child(path, "points"), "expected 3 points (start, middle, end), got " + std::to_string(p.size()));
        c = std::make_shared<ArcCurve>(ArcCurve::throughPoints(p[0], p[1], p[2], ref));
      } else {
        checkKeys(v, path, {"type", "ref", "reversed", "center", "radius", "start", "end"});
        c = std::make_shared<ArcCurve>(pointField(v, path, "center"), positiveField(v, path, "radius"),
                                       numberField(v, path, "start"), numberField(v, path, "end"), ref);
      }
    } else if (type == "circle") {
      checkKeys(v, path, {"type", "ref", "reversed", "center", "radius"});
      c = std::make_shared<ArcCurve>(
          ArcCurve::circle(pointField(v, path, "center"), positiveField(v, path, "radius"), ref));
    } else if (type == "polyline") {
      checkKeys(v, path, {"type", "ref", "reversed", "points"});
      c = std::make_shared<PolylineCurve>(points(member(v, path, "points"), child(path, "points"), 2), ref);
    } else if (type == "bezier") {
      checkKeys(v, path, {"type", "ref", "reversed", "points"});
      const auto p = points(member(v, path, "points"), child(path, "points"), 4);
      if (p.size() != 4) fail(child(path, "points"), "expected 4 control points, got " + std::to_string(p.size()));
      c = std::make_shared<BezierCurve>(p[0], p[1], p[2], p[3], ref);
    } else if (type == "bspline") {
      checkKeys(v, path, {"type", "ref", "reversed", "points"});
      c = std::make_shared<BSplineCurve>(points(member(v, path, "points"), child(path, "points"), 4), ref);
    } else {
      fail(child(path, "type"),
           "unknown curve type '" + type + "' (expected line, arc, circle, polyline, bezier or bspline)");
    }
  } catch (const Error& e) {
    // Values checked here already name their path; constructor errors get the curve's.
    if (e.code() == ErrorCode::ParseError || std::string(e.what()).rfind(path, 0) == 0) throw;
    throw Error(e.code(), path + ": " + e.what());
  }
  return {c, reversed};
}

Contour parseContour(const json& v, const std::string& path, int defaultRef) {
  if (!v.is_array()) fail(path, std::string("expected an array of curves, got ") + typeName(v));
  if (v.empty()) fail(path, "expected at least one curve");
  Contour contour;
  for (size_t i = 0; i < v.size(); ++i) contour.curves.push_back(parseCurve(v[i], index(path, i), defaultRef));
  return contour;
}

MetricSizes parseMetric(const json& v, const std::string& path) {
  expectObject(v, path);
  checkKeys(v, path, {"alpha", "h1", "h2"});
  MetricSizes m;
  m.alpha = v.contains("alpha") ? number(v["alpha"], child(path, "alpha")) : 0.0;
  m.h1 = positiveField(v, path, "h1");
  m.h2 = v.contains("h2") ? positive(v["h2"], child(path, "h2")) : m.h1;
  return m;
}

AnalyticFieldSpec parseAnalytic(const json& v, const std::string& path) {
  AnalyticFieldSpec a;
  a.field = string(member(v, path, "field"), child(path, "field"));
  a.path = path;
  if (a.field == "expression") {
    checkKeys(v, path, {"type", "field", "alpha", "h1", "h2"});
    // Compiled here only to report syntax errors with the JSON path and the column.
    auto formula = [&](const char* key, bool required, const std::string& fallback) {
      if (!v.contains(key)) {
        if (required) fail(child(path, key), "missing field");
        return fallback;
      }
      std::string text;
      if (v[key].is_number())
        text = v[key].dump();
      else
        text = string(v[key], child(path, key));
      ExpressionOptions o;
      o.name = child(path, key);
      o.uName = "x";
      o.vName = "y";
      Expression::parse(text, o);
      return text;
    };
    a.alpha = formula("alpha", false, "0");
    a.h1 = formula("h1", true, "");
    a.h2 = formula("h2", false, a.h1);
    return a;
  }
  if (a.field == "boundary_layer") {
    checkKeys(v, path, {"type", "field", "p1", "p2", "h0", "hTangent", "thickness"});
    a.p1 = pointField(v, path, "p1");
    a.p2 = pointField(v, path, "p2");
    require((a.p2 - a.p1).norm() > 0, ErrorCode::InvalidArgument,
            path + ": p1 and p2 must differ (they define the wall line)");
  } else if (a.field == "shear_layer_circle") {
    checkKeys(v, path, {"type", "field", "center", "radius", "h0", "hTangent", "thickness"});
    a.center = pointField(v, path, "center");
    a.radius = positiveField(v, path, "radius");
  } else if (a.field == "point") {
    checkKeys(v, path, {"type", "field", "center", "h0", "growth"});
    a.center = pointField(v, path, "center");
    a.h0 = positiveField(v, path, "h0");
    a.growth = numberField(v, path, "growth");
    require(a.growth >= 0, ErrorCode::InvalidArgument, child(path, "growth") + ": must be >= 0");
    return a;
  } else {
    fail(child(path, "field"),
         "unknown analytic field '" + a.field + "' (expected boundary_layer, shear_layer_circle, point or expression)");
  }
  a.h0 = positiveField(v, path, "h0");
  a.hTangent = positiveField(v, path, "hTangent");
  a.thickness = positiveField(v, path, "thickness");
  return a;
}

SourceSpec parseSource(const json& v, const std::string& path) {
  expectObject(v, path);
  const std::string type = string(member(v, path, "type"), child(path, "type"));
  SourceSpec s;
  if (type == "radial") {
    checkKeys(v, path, {"type", "center", "metric", "radius"});
    s.type = SourceType::Radial;
    s.center = pointField(v, path, "center");
  } else if (type == "segment") {
    checkKeys(v, path, {"type", "p1", "p2", "metric", "radius"});
    s.type = SourceType::Segment;
    s.p1 = pointField(v, path, "p1");
    s.p2 = pointField(v, path, "p2");
  } else if (type == "polyline") {
    checkKeys(v, path, {"type", "points", "metric", "radius"});
    s.type = SourceType::Polyline;
    s.points = points(member(v, path, "points"), child(path, "points"), 2);
  } else if (type == "nodes") {
    checkKeys(v, path, {"type", "points", "metrics"});
    s.type = SourceType::Nodes;
    s.points = points(member(v, path, "points"), child(path, "points"), 1);
    const json& ms = member(v, path, "metrics");
    const std::string mp = child(path, "metrics");
    if (!ms.is_array()) fail(mp, std::string("expected an array of metrics, got ") + typeName(ms));
    if (ms.size() != s.points.size())
      fail(mp,
           "expected one metric per point (" + std::to_string(s.points.size()) + "), got " + std::to_string(ms.size()));
    for (size_t i = 0; i < ms.size(); ++i) s.metrics.push_back(parseMetric(ms[i], index(mp, i)));
    return s;
  } else if (type == "analytic") {
    s.type = SourceType::Analytic;
    s.analytic = parseAnalytic(v, path);
    return s;
  } else {
    fail(child(path, "type"),
         "unknown source type '" + type + "' (expected radial, segment, polyline, nodes or analytic)");
  }
  s.metric = parseMetric(member(v, path, "metric"), child(path, "metric"));
  s.radius = number(member(v, path, "radius"), child(path, "radius"));
  require(s.radius >= 0, ErrorCode::InvalidArgument,
          child(path, "radius") + ": must be >= 0, got " + std::to_string(s.radius));
  return s;
}

CaseControlSpaceSpec parseControlSpace(const json& v, const std::string& path) {
  expectObject(v, path);
  checkKeys(v, path, {"kind", "hmin", "hmax", "gradation", "interpolation", "refineThreshold", "maxLevel"});
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
      fail(child(path, "maxElements"), std::string("expected an integer, got ") + typeName(m));
    o.maxElements = m.get<std::int64_t>();
    require(o.maxElements > 0, ErrorCode::InvalidArgument, child(path, "maxElements") + ": must be positive");
  }
  return o;
}

}  // namespace

CaseSpec parseCaseJson(const std::string& text) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(ErrorCode::ParseError, std::string("(root): malformed JSON: ") + e.what());
  }
  return parseCaseJsonTree(root);
}

CaseSpec parseCaseJsonTree(const json& root) {
  expectObject(root, "");
  checkKeys(root, "", {"domain", "controlSpace", "sources", "options", "name", "description"});
  CaseSpec spec;
  const json& domain = member(root, "", "domain");
  expectObject(domain, "domain");
  checkKeys(domain, "domain", {"outer", "holes"});
  spec.domain.outer = parseContour(member(domain, "domain", "outer"), "domain.outer", 1);
  if (domain.contains("holes")) {
    const json& holes = domain["holes"];
    if (!holes.is_array()) fail("domain.holes", std::string("expected an array of contours, got ") + typeName(holes));
    for (size_t i = 0; i < holes.size(); ++i)
      spec.domain.holes.push_back(parseContour(holes[i], index("domain.holes", i), int(i) + 2));
  }
  spec.controlSpace = parseControlSpace(member(root, "", "controlSpace"), "controlSpace");
  if (root.contains("sources")) {
    const json& s = root["sources"];
    if (!s.is_array()) fail("sources", std::string("expected an array, got ") + typeName(s));
    for (size_t i = 0; i < s.size(); ++i) spec.sources.push_back(parseSource(s[i], index("sources", i)));
  }
  if (root.contains("options")) spec.options = parseOptions(root["options"], "options");
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

}  // namespace anisomesh

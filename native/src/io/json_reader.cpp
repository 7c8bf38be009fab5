#include "json_reader.h"

#include "anisomesh/io/json_text.h"

#include <cmath>
#include <memory>

#include "anisomesh/core/number_text.h"
#include "anisomesh/geometry/expression.h"

namespace anisomesh {
namespace json_reader {

void fail(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::ParseError, (path.empty() ? std::string("(root)") : path) + ": " + what);
}

std::string child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string index(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

json parseText(const std::string& text) {
  requireNoNulByte(text);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number overflow (1e999)
    throw Error(ErrorCode::ParseError, std::string("(root): malformed JSON: ") + e.what());
  }
}

void expectObject(const json& v, const std::string& path) {
  if (!v.is_object()) fail(path, std::string("expected an object, got ") + v.type_name());
}

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

const json& array(const json& v, const std::string& path, const char* items) {
  if (!v.is_array()) fail(path, std::string("expected an array of ") + items + ", got " + v.type_name());
  return v;
}

double number(const json& v, const std::string& path) {
  if (!v.is_number()) fail(path, std::string("expected a number, got ") + v.type_name());
  const double x = v.get<double>();
  require(std::isfinite(x), ErrorCode::InvalidArgument, path + ": must be finite");
  return x;
}

double positive(const json& v, const std::string& path) {
  const double x = number(v, path);
  require(x > 0, ErrorCode::InvalidArgument, path + ": must be positive, got " + std::to_string(x));
  return x;
}

bool boolean(const json& v, const std::string& path) {
  if (!v.is_boolean()) fail(path, std::string("expected true or false, got ") + v.type_name());
  return v.get<bool>();
}

std::string string(const json& v, const std::string& path) {
  if (!v.is_string()) fail(path, std::string("expected a string, got ") + v.type_name());
  return v.get<std::string>();
}

int integer(const json& v, const std::string& path) {
  if (!v.is_number_integer()) fail(path, std::string("expected an integer, got ") + v.type_name());
  const auto x = v.get<long long>();
  if (x < -2147483647LL || x > 2147483647LL) fail(path, "integer out of range");
  return int(x);
}

Vec2 point(const json& v, const std::string& path, const char* form) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    fail(path, std::string("expected a point ") + form + ", got " +
                   (v.is_array() ? "an array of " + std::to_string(v.size()) : std::string(v.type_name())));
  return {number(v[0], index(path, 0)), number(v[1], index(path, 1))};
}

Vec3 point3(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    fail(path, std::string("expected a point [x, y, z], got ") +
                   (v.is_array() ? "an array of " + std::to_string(v.size()) : std::string(v.type_name())));
  return {number(v[0], index(path, 0)), number(v[1], index(path, 1)), number(v[2], index(path, 2))};
}

std::vector<Vec2> points(const json& v, const std::string& path, size_t minCount, const char* form) {
  array(v, path, "points");
  if (v.size() < minCount)
    fail(path, "expected at least " + std::to_string(minCount) + " points, got " + std::to_string(v.size()));
  std::vector<Vec2> out;
  for (size_t i = 0; i < v.size(); ++i) out.push_back(point(v[i], index(path, i), form));
  return out;
}

Box2 box(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 2) fail(path, "expected [[u0, v0], [u1, v1]]");
  Box2 b{point(v[0], index(path, 0), "[u, v]"), point(v[1], index(path, 1), "[u, v]")};
  require(b.hi.x() > b.lo.x() && b.hi.y() > b.lo.y(), ErrorCode::InvalidDomain,
          path + ": empty or inverted parameter domain");
  return b;
}

CurveUse parseCurve(const json& v, const std::string& path, int defaultRef, const char* form) {
  expectObject(v, path);
  const std::string type = string(member(v, path, "type"), child(path, "type"));
  const int ref = v.contains("ref") ? integer(v["ref"], child(path, "ref")) : defaultRef;
  const bool reversed = v.contains("reversed") && boolean(v["reversed"], child(path, "reversed"));
  auto pointsField = [&](size_t minCount) {
    return points(member(v, path, "points"), child(path, "points"), minCount, form);
  };
  CurvePtr c = withPath(path, [&]() -> CurvePtr {
    if (type == "line") {
      checkKeys(v, path, {"type", "ref", "reversed", "p1", "p2"});
      return std::make_shared<LineCurve>(pointField(v, path, "p1", form), pointField(v, path, "p2", form), ref);
    }
    if (type == "arc") {
      if (v.contains("points")) {
        checkKeys(v, path, {"type", "ref", "reversed", "points"});
        const auto p = pointsField(3);
        if (p.size() != 3)
          fail(child(path, "points"), "expected 3 points (start, middle, end), got " + std::to_string(p.size()));
        return std::make_shared<ArcCurve>(ArcCurve::throughPoints(p[0], p[1], p[2], ref));
      }
      checkKeys(v, path, {"type", "ref", "reversed", "center", "radius", "start", "end"});
      return std::make_shared<ArcCurve>(pointField(v, path, "center", form), positiveField(v, path, "radius"),
                                        numberField(v, path, "start"), numberField(v, path, "end"), ref);
    }
    if (type == "circle") {
      checkKeys(v, path, {"type", "ref", "reversed", "center", "radius"});
      return std::make_shared<ArcCurve>(
          ArcCurve::circle(pointField(v, path, "center", form), positiveField(v, path, "radius"), ref));
    }
    if (type == "polyline") {
      checkKeys(v, path, {"type", "ref", "reversed", "points"});
      return std::make_shared<PolylineCurve>(pointsField(2), ref);
    }
    if (type == "bezier") {
      checkKeys(v, path, {"type", "ref", "reversed", "points"});
      const auto p = pointsField(4);
      if (p.size() != 4) fail(child(path, "points"), "expected 4 control points, got " + std::to_string(p.size()));
      return std::make_shared<BezierCurve>(p[0], p[1], p[2], p[3], ref);
    }
    if (type == "bspline") {
      checkKeys(v, path, {"type", "ref", "reversed", "points"});
      return std::make_shared<BSplineCurve>(pointsField(4), ref);
    }
    fail(child(path, "type"),
         "unknown curve type '" + type + "' (expected line, arc, circle, polyline, bezier or bspline)");
  });
  return {c, reversed};
}

Contour parseContour(const json& v, const std::string& path, int defaultRef, const char* form) {
  array(v, path, "curves");
  if (v.empty()) fail(path, "expected at least one curve");
  Contour contour;
  for (size_t i = 0; i < v.size(); ++i) contour.curves.push_back(parseCurve(v[i], index(path, i), defaultRef, form));
  return contour;
}

MetricSizes parseMetric(const json& v, const std::string& path) {
  expectObject(v, path);
  checkKeys(v, path, {"alpha", "h1", "h2"});
  MetricSizes m;
  m.alpha = numberOr(v, path, "alpha", 0.0);
  m.h1 = positiveField(v, path, "h1");
  m.h2 = positiveOr(v, path, "h2", m.h1);
  return m;
}

namespace {

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

const char* sourceTypeName(SourceType t) {
  switch (t) {
    case SourceType::Radial:
      return "radial";
    case SourceType::Segment:
      return "segment";
    case SourceType::Polyline:
      return "polyline";
    case SourceType::Curve:
      return "curve";
    case SourceType::Nodes:
      return "nodes";
    case SourceType::Analytic:
      return "analytic";
  }
  return "";
}

}  // namespace

BoundaryUpdateOptions parseBoundaryRules(const json& v, const std::string& path, bool planar) {
  expectObject(v, path);
  if (planar)
    checkKeys(v, path,
              {"eps1", "lengthMin", "lengthMax", "eps2", "dMax", "chordTolerance", "gapElements", "maxRounds"});
  else
    checkKeys(v, path, {"eps1", "lengthMin", "lengthMax", "eps2", "dMax"});
  BoundaryUpdateOptions o;
  o.eps1 = positiveOr(v, path, "eps1", o.eps1);
  // Above 1 a unit segment counts as short, so every round would update the control space again.
  require(o.eps1 <= 1.0, ErrorCode::InvalidArgument,
          child(path, "eps1") + ": must be in (0, 1], got " + numberText(o.eps1));
  o.lengthMin = positiveOr(v, path, "lengthMin", o.lengthMin);
  o.lengthMax = positiveOr(v, path, "lengthMax", o.lengthMax);
  require(o.lengthMin <= 1.0 && o.lengthMax >= 1.0, ErrorCode::InvalidArgument,
          path + ": lengthMin <= 1 <= lengthMax is needed (unit segments are valid), got [" + numberText(o.lengthMin) +
              ", " + numberText(o.lengthMax) + "]");
  o.eps2 = positiveOr(v, path, "eps2", o.eps2);
  o.dMax = positiveOr(v, path, "dMax", o.dMax);
  require(o.dMax >= 1.0, ErrorCode::InvalidArgument, child(path, "dMax") + ": must be >= 1, got " + numberText(o.dMax));
  o.chordTolerance = positiveOr(v, path, "chordTolerance", o.chordTolerance);
  o.gapElements = positiveOr(v, path, "gapElements", o.gapElements);
  if (v.contains("maxRounds")) {
    o.maxRounds = integer(v["maxRounds"], child(path, "maxRounds"));
    require(o.maxRounds >= 0 && o.maxRounds <= 64, ErrorCode::InvalidArgument,
            child(path, "maxRounds") + ": must be in [0, 64], got " + std::to_string(o.maxRounds));
  }
  return o;
}

SourceSpec parseSource(const json& v, const std::string& path, std::initializer_list<SourceType> allowed) {
  expectObject(v, path);
  const std::string type = string(member(v, path, "type"), child(path, "type"));
  SourceSpec s;
  bool known = false;
  for (SourceType t : allowed)
    if (type == sourceTypeName(t)) s.type = t, known = true;
  if (!known) {
    std::string list;
    size_t k = 0;
    for (SourceType t : allowed) {
      if (k > 0) list += k + 1 == allowed.size() ? " or " : ", ";
      list += sourceTypeName(t);
      ++k;
    }
    fail(child(path, "type"), "unknown source type '" + type + "' (expected " + list + ")");
  }
  switch (s.type) {
    case SourceType::Radial:
      checkKeys(v, path, {"type", "center", "metric", "radius"});
      s.center = pointField(v, path, "center");
      break;
    case SourceType::Segment:
      checkKeys(v, path, {"type", "p1", "p2", "metric", "radius"});
      s.p1 = pointField(v, path, "p1");
      s.p2 = pointField(v, path, "p2");
      break;
    case SourceType::Polyline:
      checkKeys(v, path, {"type", "points", "metric", "radius"});
      s.points = points(member(v, path, "points"), child(path, "points"), 2);
      break;
    case SourceType::Curve: {
      checkKeys(v, path, {"type", "curve", "t1", "t2", "metric", "radius"});
      s.curve = parseCurve(member(v, path, "curve"), child(path, "curve"), 0).curve;
      s.t1 = numberOr(v, path, "t1", 0.0);
      s.t2 = numberOr(v, path, "t2", 1.0);
      require(s.t1 >= 0.0 && s.t1 < s.t2 && s.t2 <= 1.0, ErrorCode::InvalidArgument,
              path + ": expected 0 <= t1 < t2 <= 1, got t1 = " + numberText(s.t1) + ", t2 = " + numberText(s.t2));
      break;
    }
    case SourceType::Nodes: {
      checkKeys(v, path, {"type", "points", "metrics"});
      s.points = points(member(v, path, "points"), child(path, "points"), 1);
      const std::string mp = child(path, "metrics");
      const json& ms = array(member(v, path, "metrics"), mp, "metrics");
      if (ms.size() != s.points.size())
        fail(mp, "expected one metric per point (" + std::to_string(s.points.size()) + "), got " +
                     std::to_string(ms.size()));
      for (size_t i = 0; i < ms.size(); ++i) s.metrics.push_back(parseMetric(ms[i], index(mp, i)));
      return s;
    }
    case SourceType::Analytic:
      s.analytic = parseAnalytic(v, path);
      return s;
  }
  s.metric = parseMetric(member(v, path, "metric"), child(path, "metric"));
  s.radius = numberField(v, path, "radius");
  require(s.radius >= 0, ErrorCode::InvalidArgument,
          child(path, "radius") + ": must be >= 0, got " + std::to_string(s.radius));
  return s;
}

}  // namespace json_reader
}  // namespace anisomesh

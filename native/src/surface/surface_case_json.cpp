#include "anisomesh/surface/surface_case_json.h"

#include <cmath>
#include <initializer_list>
#include <map>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

using json = nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::ParseError, (path.empty() ? std::string("(root)") : path) + ": " + what);
}
std::string at(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string at(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

void object(const json& v, const std::string& path) {
  if (!v.is_object()) fail(path, std::string("expected an object, got ") + v.type_name());
}

// Unknown keys are errors: a typo must not fall back to a default silently.
void keys(const json& v, const std::string& path, std::initializer_list<const char*> allowed) {
  for (auto it = v.begin(); it != v.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (ok) continue;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    fail(at(path, it.key()), "unknown field (expected one of: " + list + ")");
  }
}

const json& need(const json& v, const std::string& path, const char* key) {
  auto it = v.find(key);
  if (it == v.end()) fail(at(path, key), "missing field");
  return *it;
}

double num(const json& v, const std::string& path) {
  if (!v.is_number()) fail(path, std::string("expected a number, got ") + v.type_name());
  const double x = v.get<double>();
  require(std::isfinite(x), ErrorCode::InvalidArgument, path + ": must be finite");
  return x;
}
double pos(const json& v, const std::string& path) {
  const double x = num(v, path);
  require(x > 0, ErrorCode::InvalidArgument, path + ": must be positive");
  return x;
}
double numOr(const json& v, const std::string& path, const char* key, double def) {
  return v.contains(key) ? num(v[key], at(path, key)) : def;
}
double posOr(const json& v, const std::string& path, const char* key, double def) {
  return v.contains(key) ? pos(v[key], at(path, key)) : def;
}
bool boolean(const json& v, const std::string& path) {
  if (!v.is_boolean()) fail(path, std::string("expected true or false, got ") + v.type_name());
  return v.get<bool>();
}
std::string str(const json& v, const std::string& path) {
  if (!v.is_string()) fail(path, std::string("expected a string, got ") + v.type_name());
  return v.get<std::string>();
}
int integer(const json& v, const std::string& path) {
  if (!v.is_number_integer()) fail(path, std::string("expected an integer, got ") + v.type_name());
  const long long x = v.get<long long>();
  if (x < -2147483647LL || x > 2147483647LL) fail(path, "integer out of range");
  return int(x);
}
Vec2 vec2(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) fail(path, "expected a point [u, v]");
  return {num(v[0], at(path, 0)), num(v[1], at(path, 1))};
}
Vec3 vec3(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    fail(path, "expected a point [x, y, z]");
  return {num(v[0], at(path, 0)), num(v[1], at(path, 1)), num(v[2], at(path, 2))};
}
std::vector<Vec2> vec2s(const json& v, const std::string& path, size_t minCount) {
  if (!v.is_array()) fail(path, std::string("expected an array of points, got ") + v.type_name());
  if (v.size() < minCount) fail(path, "expected at least " + std::to_string(minCount) + " points");
  std::vector<Vec2> out;
  for (size_t i = 0; i < v.size(); ++i) out.push_back(vec2(v[i], at(path, i)));
  return out;
}
Box2 box(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 2) fail(path, "expected [[u0, v0], [u1, v1]]");
  Box2 b{vec2(v[0], at(path, 0)), vec2(v[1], at(path, 1))};
  require(b.hi.x() > b.lo.x() && b.hi.y() > b.lo.y(), ErrorCode::InvalidDomain,
          path + ": empty or inverted parameter domain");
  return b;
}

// Constructor errors get the JSON path in front.
template <class F>
auto withPath(const std::string& path, F f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error& e) {
    if (std::string(e.what()).rfind(path, 0) == 0) throw;
    throw Error(e.code(), path + ": " + e.what());
  }
}

Expression formula(const json& v, const std::string& path, const char* key, const char* name) {
  const std::string text = str(need(v, path, key), at(path, key));
  ExpressionOptions o;
  o.name = name;
  return withPath(at(path, key), [&] { return Expression::parse(text, o); });
}

std::shared_ptr<const Surface> parseSurface(const json& v, const std::string& path, const std::string& defName) {
  object(v, path);
  const std::string type = str(need(v, path, "type"), at(path, "type"));
  const std::string name = v.contains("name") ? str(v["name"], at(path, "name")) : defName;
  auto dom = [&](const Box2& def) { return v.contains("domain") ? box(v["domain"], at(path, "domain")) : def; };
  const double twoPi = 6.283185307179586;
  return withPath(path, [&]() -> std::shared_ptr<const Surface> {
    if (type == "expression") {
      keys(v, path, {"type", "name", "x", "y", "z", "domain"});
      return std::make_shared<ExpressionSurface>(formula(v, path, "x", "x(u,v)"), formula(v, path, "y", "y(u,v)"),
                                                 formula(v, path, "z", "z(u,v)"),
                                                 box(need(v, path, "domain"), at(path, "domain")), name);
    }
    if (type == "heightfield") {
      keys(v, path, {"type", "name", "z", "domain"});
      return std::make_shared<HeightFieldSurface>(formula(v, path, "z", "z(u,v)"),
                                                  box(need(v, path, "domain"), at(path, "domain")), name);
    }
    if (type == "p2") {
      keys(v, path, {"type", "name", "domain"});
      return paperP2(dom({{-10, -10}, {10, 10}}));
    }
    Vec3 center = v.contains("center") ? vec3(v["center"], at(path, "center")) : Vec3::Zero();
    if (type == "plane") {
      keys(v, path, {"type", "name", "origin", "a1", "a2", "domain"});
      return std::make_shared<PlaneSurface>(v.contains("origin") ? vec3(v["origin"], at(path, "origin")) : Vec3::Zero(),
                                            v.contains("a1") ? vec3(v["a1"], at(path, "a1")) : Vec3::UnitX(),
                                            v.contains("a2") ? vec3(v["a2"], at(path, "a2")) : Vec3::UnitY(),
                                            dom({{0, 0}, {1, 1}}));
    }
    if (type == "sphere") {
      keys(v, path, {"type", "name", "radius", "center", "domain"});
      return std::make_shared<SphereSurface>(pos(need(v, path, "radius"), at(path, "radius")), center,
                                             dom({{0.0, -1.4}, {twoPi, 1.4}}));
    }
    if (type == "cylinder") {
      keys(v, path, {"type", "name", "radius", "center", "domain"});
      return std::make_shared<CylinderSurface>(pos(need(v, path, "radius"), at(path, "radius")), center,
                                               dom({{0.0, 0.0}, {twoPi, 1.0}}));
    }
    if (type == "torus") {
      keys(v, path, {"type", "name", "majorRadius", "minorRadius", "center", "domain"});
      const double R = pos(need(v, path, "majorRadius"), at(path, "majorRadius"));
      const double r = pos(need(v, path, "minorRadius"), at(path, "minorRadius"));
      require(r < R, ErrorCode::InvalidArgument, at(path, "minorRadius") + ": must be below majorRadius");
      return std::make_shared<TorusSurface>(R, r, center, dom({{0.0, 0.0}, {twoPi, twoPi}}));
    }
    if (type == "bezier") {
      keys(v, path, {"type", "name", "points"});
      const json& p = need(v, path, "points");
      const std::string pp = at(path, "points");
      if (!p.is_array() || p.size() != 4) fail(pp, "expected 4 rows of 4 control points [x, y, z]");
      std::array<std::array<Vec3, 4>, 4> cp;
      for (size_t i = 0; i < 4; ++i) {
        if (!p[i].is_array() || p[i].size() != 4) fail(at(pp, i), "expected 4 control points [x, y, z]");
        for (size_t j = 0; j < 4; ++j) cp[i][j] = vec3(p[i][j], at(at(pp, i), j));
      }
      return std::make_shared<BezierPatchSurface>(cp, name);
    }
    fail(at(path, "type"), "unknown surface type '" + type +
                               "' (expected expression, heightfield, plane, sphere, cylinder, torus, bezier or p2)");
  });
}

// A trimming curve in (u, v), the syntax of CASE_FORMAT.md.
CurveUse parseCurve(const json& v, const std::string& path, int defRef) {
  object(v, path);
  const std::string type = str(need(v, path, "type"), at(path, "type"));
  const int ref = v.contains("ref") ? integer(v["ref"], at(path, "ref")) : defRef;
  const bool rev = v.contains("reversed") && boolean(v["reversed"], at(path, "reversed"));
  CurvePtr c = withPath(path, [&]() -> CurvePtr {
    if (type == "line") {
      keys(v, path, {"type", "ref", "reversed", "p1", "p2"});
      return std::make_shared<LineCurve>(vec2(need(v, path, "p1"), at(path, "p1")),
                                         vec2(need(v, path, "p2"), at(path, "p2")), ref);
    }
    if (type == "arc") {
      if (v.contains("points")) {
        keys(v, path, {"type", "ref", "reversed", "points"});
        const auto p = vec2s(v["points"], at(path, "points"), 3);
        if (p.size() != 3) fail(at(path, "points"), "expected 3 points (start, middle, end)");
        return std::make_shared<ArcCurve>(ArcCurve::throughPoints(p[0], p[1], p[2], ref));
      }
      keys(v, path, {"type", "ref", "reversed", "center", "radius", "start", "end"});
      return std::make_shared<ArcCurve>(
          vec2(need(v, path, "center"), at(path, "center")), pos(need(v, path, "radius"), at(path, "radius")),
          num(need(v, path, "start"), at(path, "start")), num(need(v, path, "end"), at(path, "end")), ref);
    }
    if (type == "circle") {
      keys(v, path, {"type", "ref", "reversed", "center", "radius"});
      return std::make_shared<ArcCurve>(ArcCurve::circle(vec2(need(v, path, "center"), at(path, "center")),
                                                         pos(need(v, path, "radius"), at(path, "radius")), ref));
    }
    if (type == "polyline") {
      keys(v, path, {"type", "ref", "reversed", "points"});
      return std::make_shared<PolylineCurve>(vec2s(need(v, path, "points"), at(path, "points"), 2), ref);
    }
    if (type == "bezier") {
      keys(v, path, {"type", "ref", "reversed", "points"});
      const auto p = vec2s(need(v, path, "points"), at(path, "points"), 4);
      if (p.size() != 4) fail(at(path, "points"), "expected 4 control points");
      return std::make_shared<BezierCurve>(p[0], p[1], p[2], p[3], ref);
    }
    if (type == "bspline") {
      keys(v, path, {"type", "ref", "reversed", "points"});
      return std::make_shared<BSplineCurve>(vec2s(need(v, path, "points"), at(path, "points"), 4), ref);
    }
    fail(at(path, "type"),
         "unknown curve type '" + type + "' (expected line, arc, circle, polyline, bezier or bspline)");
  });
  return {c, rev};
}

Contour parseContour(const json& v, const std::string& path, int defRef) {
  if (!v.is_array() || v.empty()) fail(path, "expected a non-empty array of curves");
  Contour c;
  for (size_t i = 0; i < v.size(); ++i) c.curves.push_back(parseCurve(v[i], at(path, i), defRef));
  return c;
}

Metric parseMetric(const json& v, const std::string& path) {
  object(v, path);
  keys(v, path, {"alpha", "h1", "h2"});
  const double h1 = pos(need(v, path, "h1"), at(path, "h1"));
  const double h2 = posOr(v, path, "h2", h1);
  return withPath(path, [&] { return Metric::fromSizes(numOr(v, path, "alpha", 0.0), h1, h2); });
}

MetricSource parseSource(const json& v, const std::string& path) {
  object(v, path);
  const std::string type = str(need(v, path, "type"), at(path, "type"));
  const double r = v.contains("radius") ? num(v["radius"], at(path, "radius")) : 0.0;
  require(r >= 0, ErrorCode::InvalidArgument, at(path, "radius") + ": must be >= 0");
  if (type == "radial") {
    keys(v, path, {"type", "center", "metric", "radius"});
    return RadialSource{vec2(need(v, path, "center"), at(path, "center")),
                        parseMetric(need(v, path, "metric"), at(path, "metric")), r};
  }
  if (type == "segment") {
    keys(v, path, {"type", "p1", "p2", "metric", "radius"});
    return SegmentSource{vec2(need(v, path, "p1"), at(path, "p1")), vec2(need(v, path, "p2"), at(path, "p2")),
                         parseMetric(need(v, path, "metric"), at(path, "metric")), r};
  }
  if (type == "polyline") {
    keys(v, path, {"type", "points", "metric", "radius"});
    return PolylineSource{vec2s(need(v, path, "points"), at(path, "points"), 2),
                          parseMetric(need(v, path, "metric"), at(path, "metric")), r};
  }
  fail(at(path, "type"), "unknown source type '" + type + "' (expected radial, segment or polyline)");
}

// The surface's parameter rectangle as the outer contour: bottom, right, top, left (refs 1-4).
Contour rectangle(const Box2& b) {
  const Vec2 p0 = b.lo, p1(b.hi.x(), b.lo.y()), p2 = b.hi, p3(b.lo.x(), b.hi.y());
  Contour c;
  c.add(std::make_shared<LineCurve>(p0, p1, 1));
  c.add(std::make_shared<LineCurve>(p1, p2, 2));
  c.add(std::make_shared<LineCurve>(p2, p3, 3));
  c.add(std::make_shared<LineCurve>(p3, p0, 4));
  return c;
}

const Curve& curveAt(const SurfacePatch& p, const CurveRef& r) {
  const Contour& c = r.contour == 0 ? p.domain.outer : p.domain.holes[size_t(r.contour - 1)];
  return *c.curves[size_t(r.curve)].curve;
}

}  // namespace

SurfaceCaseSpec parseSurfaceCaseJson(const std::string& text) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(ErrorCode::ParseError, std::string("(root): malformed JSON: ") + e.what());
  }
  return parseSurfaceCaseJsonTree(root);
}

SurfaceCaseSpec parseSurfaceCaseJsonTree(const json& root) {
  object(root, "");
  keys(root, "",
       {"name", "description", "metric", "adaptation", "options", "surfaces", "patches", "shared", "sources3d"});
  SurfaceCaseSpec spec;
  SurfaceMeshOptions& o = spec.options;
  if (root.contains("metric")) {
    const json& m = root["metric"];
    object(m, "metric");
    keys(m, "metric",
         {"chordTolerance", "chordSafety", "angleTolerance", "hmin", "hmax", "maxAspectRatio", "gradation",
          "contourCurvature"});
    if (m.contains("contourCurvature")) o.contourCurvature = boolean(m["contourCurvature"], "metric.contourCurvature");
    o.chordSafety = m.contains("chordSafety") ? num(m["chordSafety"], "metric.chordSafety") : kDefaultChordSafety;
    require(std::isfinite(o.chordSafety) && o.chordSafety > 0.0, ErrorCode::InvalidArgument,
            "metric.chordSafety: must be > 0");
    o.metric.chordTolerance = numOr(m, "metric", "chordTolerance", o.metric.chordTolerance);
    o.metric.angleTolerance = numOr(m, "metric", "angleTolerance", o.metric.angleTolerance);
    o.metric.hmin = posOr(m, "metric", "hmin", o.metric.hmin);
    o.metric.hmax = posOr(m, "metric", "hmax", o.metric.hmax);
    o.metric.maxAspectRatio = posOr(m, "metric", "maxAspectRatio", o.metric.maxAspectRatio);
    if (m.contains("gradation")) {
      o.gradation = m["gradation"].is_null() ? 0.0 : num(m["gradation"], "metric.gradation");
      require(o.gradation == 0.0 || o.gradation >= 1.0, ErrorCode::InvalidArgument,
              "metric.gradation: must be >= 1 (or null: off)");
    }
    withPath("metric", [&] { validate(o.metric); });
  }
  if (root.contains("adaptation")) o.adaptation = boolean(root["adaptation"], "adaptation");
  if (root.contains("options")) {
    const json& v = root["options"];
    object(v, "options");
    keys(v, "options", {"maxElements", "maxRounds", "improvementPasses", "quads", "allQuads"});
    if (v.contains("quads")) o.quads = boolean(v["quads"], "options.quads");
    if (v.contains("allQuads")) o.allQuads = boolean(v["allQuads"], "options.allQuads");
    if (v.contains("maxElements")) {
      o.mesher.maxElements = integer(v["maxElements"], "options.maxElements");
      require(o.mesher.maxElements > 0, ErrorCode::InvalidArgument, "options.maxElements: must be positive");
    }
    if (v.contains("maxRounds")) o.maxRounds = std::max(1, integer(v["maxRounds"], "options.maxRounds"));
    if (v.contains("improvementPasses"))
      o.mesher.improvementPasses = std::max(0, integer(v["improvementPasses"], "options.improvementPasses"));
  }
  std::map<std::string, std::shared_ptr<const Surface>> named;
  if (root.contains("surfaces")) {
    object(root["surfaces"], "surfaces");
    for (auto it = root["surfaces"].begin(); it != root["surfaces"].end(); ++it)
      named[it.key()] = parseSurface(it.value(), at("surfaces", it.key()), it.key());
  }
  const json& patches = need(root, "", "patches");
  if (!patches.is_array() || patches.empty()) fail("patches", "expected a non-empty array of patches");
  std::map<std::string, int> patchIndex;
  for (size_t i = 0; i < patches.size(); ++i) {
    const std::string path = at("patches", i);
    const json& v = patches[i];
    object(v, path);
    keys(v, path, {"name", "id", "surface", "outer", "holes", "sources"});
    SurfacePatch p;
    p.name = v.contains("name") ? str(v["name"], at(path, "name")) : std::to_string(i);
    p.id = v.contains("id") ? integer(v["id"], at(path, "id")) : int(i) + 1;
    const json& s = need(v, path, "surface");
    if (s.is_string()) {
      auto it = named.find(s.get<std::string>());
      if (it == named.end()) fail(at(path, "surface"), "no surface named '" + s.get<std::string>() + "' in surfaces");
      p.surface = it->second;
    } else {
      p.surface = parseSurface(s, at(path, "surface"), p.name);
    }
    p.domain.outer =
        v.contains("outer") ? parseContour(v["outer"], at(path, "outer"), 1) : rectangle(p.surface->domain());
    if (v.contains("holes")) {
      const json& h = v["holes"];
      if (!h.is_array()) fail(at(path, "holes"), "expected an array of contours");
      for (size_t k = 0; k < h.size(); ++k)
        p.domain.holes.push_back(parseContour(h[k], at(at(path, "holes"), k), int(k) + 2));
    }
    if (v.contains("sources")) {
      const json& ss = v["sources"];
      if (!ss.is_array()) fail(at(path, "sources"), "expected an array of sources");
      for (size_t k = 0; k < ss.size(); ++k) p.sources.push_back(parseSource(ss[k], at(at(path, "sources"), k)));
    }
    if (patchIndex.count(p.name)) fail(at(path, "name"), "duplicate patch name '" + p.name + "'");
    patchIndex[p.name] = int(i);
    spec.model.patches.push_back(std::move(p));
  }
  if (root.contains("shared")) {
    const json& sh = root["shared"];
    if (!sh.is_array()) fail("shared", "expected an array");
    for (size_t i = 0; i < sh.size(); ++i) {
      const std::string path = at("shared", i);
      object(sh[i], path);
      keys(sh[i], path, {"a", "b", "reversed"});
      auto ref = [&](const char* key) {
        const std::string rp = at(path, key);
        const json& r = need(sh[i], path, key);
        object(r, rp);
        keys(r, rp, {"patch", "contour", "curve"});
        CurveRef c;
        const json& pj = need(r, rp, "patch");
        if (pj.is_string()) {
          auto it = patchIndex.find(pj.get<std::string>());
          if (it == patchIndex.end()) fail(at(rp, "patch"), "no patch named '" + pj.get<std::string>() + "'");
          c.patch = it->second;
        } else {
          c.patch = integer(pj, at(rp, "patch"));
          if (c.patch < 0 || c.patch >= int(spec.model.patches.size())) fail(at(rp, "patch"), "no such patch");
        }
        c.contour = r.contains("contour") ? integer(r["contour"], at(rp, "contour")) : 0;
        c.curve = integer(need(r, rp, "curve"), at(rp, "curve"));
        const SurfacePatch& p = spec.model.patches[size_t(c.patch)];
        if (c.contour < 0 || c.contour > int(p.domain.holes.size())) fail(at(rp, "contour"), "no such contour");
        const Contour& ct = c.contour == 0 ? p.domain.outer : p.domain.holes[size_t(c.contour - 1)];
        if (c.curve < 0 || c.curve >= int(ct.curves.size())) fail(at(rp, "curve"), "no such curve");
        return c;
      };
      SharedCurve s{ref("a"), ref("b"), false};
      if (sh[i].contains("reversed")) {
        s.reversed = boolean(sh[i]["reversed"], at(path, "reversed"));
      } else {
        // Orientation from 3D: which way round b passes a's inner points.
        const SurfacePatch& pa = spec.model.patches[size_t(s.a.patch)];
        const SurfacePatch& pb = spec.model.patches[size_t(s.b.patch)];
        const Curve& ca = curveAt(pa, s.a);
        const Curve& cb = curveAt(pb, s.b);
        double same = 0, opposite = 0;
        for (double t : {0.3, 0.5, 0.7}) {
          const Vec3 x = pa.surface->point(ca.point(t));
          same += (pb.surface->point(cb.point(t)) - x).norm();
          opposite += (pb.surface->point(cb.point(1.0 - t)) - x).norm();
        }
        s.reversed = opposite < same;
      }
      spec.model.shared.push_back(s);
    }
  }
  if (root.contains("sources3d")) {
    const json& ss = root["sources3d"];
    if (!ss.is_array()) fail("sources3d", "expected an array");
    for (size_t i = 0; i < ss.size(); ++i) {
      const std::string path = at("sources3d", i);
      object(ss[i], path);
      keys(ss[i], path, {"type", "center", "h", "radius"});
      if (ss[i].contains("type") && str(ss[i]["type"], at(path, "type")) != "radial")
        fail(at(path, "type"), "only 'radial' 3D sources are supported");
      Source3D s;
      s.center = vec3(need(ss[i], path, "center"), at(path, "center"));
      s.h = pos(need(ss[i], path, "h"), at(path, "h"));
      s.radius = num(need(ss[i], path, "radius"), at(path, "radius"));
      require(s.radius >= 0, ErrorCode::InvalidArgument, at(path, "radius") + ": must be >= 0");
      spec.model.sources3d.push_back(s);
    }
  }
  return spec;
}

bool isSurfaceCaseJson(const std::string& text) {
  try {
    return isSurfaceCaseJsonTree(json::parse(text));
  } catch (const json::parse_error&) {
    return false;
  }
}

bool isSurfaceCaseJsonTree(const json& root) { return root.is_object() && root.contains("patches"); }

Mesh meshSurfaceCase(const SurfaceCaseSpec& spec, SurfaceMeshReport* report) {
  return meshSurfaceModel(spec.model, spec.options, report);
}

Mesh meshSurfaceCase(const std::string& jsonText, SurfaceMeshReport* report) {
  return meshSurfaceCase(parseSurfaceCaseJson(jsonText), report);
}

json surfaceMeshReportToJson(const SurfaceMeshReport& r) {
  const Surface3DQuality& q = r.quality;
  return json{{"patches", r.patches},
              {"rounds", r.rounds},
              {"invalidations", r.invalidations},
              {"vertices", r.vertices},
              {"triangles", r.triangles},
              {"patchTriangles", r.patchTriangles},
              {"sharedEdges", r.sharedEdges},
              {"crossSharedSizeRatioMax", r.crossSharedSizeRatioMax},
              {"quality3d",
               {{"edges", q.edges},
                {"edgesWithinSqrt2", q.edgesWithinSqrt2},
                {"edgeLengthMin", q.edgeLengthMin},
                {"edgeLengthMean", q.edgeLengthMean},
                {"edgeLengthMax", q.edgeLengthMax},
                {"qualityMean", q.qualityMean},
                {"qualityMin", q.qualityMin},
                {"chordDeviationMax", q.chordDeviationMax},
                {"chordDeviationMaxRelative", q.chordDeviationMaxRelative},
                {"edgeChordDeviationMax", q.edgeChordDeviationMax},
                {"isoChordDeviationMax", q.isoChordDeviationMax},
                {"inverted", q.inverted}}},
              {"curvatureEvaluations", r.curvatureEvaluations},
              {"curvatureSeconds", r.curvatureSeconds},
              {"controlSpaceQueries", r.controlSpaceQueries},
              {"controlSpaceSeconds", r.controlSpaceSeconds},
              {"secondsTotal", r.secondsTotal}};
}

}  // namespace anisomesh

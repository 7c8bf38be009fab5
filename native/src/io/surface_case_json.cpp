// The surface case reader (examples/SURFACE_FORMAT.md): surfaces, trimmed patches in
// (u, v), shared curves, the surface metric options, user sources and the adaptation
// switch. Curves, contours and sources are read as in planar cases (json_reader.h).
#include <array>
#include <cmath>
#include <map>
#include <memory>

#include "anisomesh/geometry/expression.h"
#include "anisomesh/io/case_json.h"
#include "json_reader.h"

namespace anisomesh {
namespace {

using namespace json_reader;  // NOLINT(google-build-using-namespace): the readers of this file

Expression formula(const json& v, const std::string& path, const char* key, const char* name) {
  const std::string text = string(member(v, path, key), child(path, key));
  ExpressionOptions o;
  o.name = name;
  return withPath(child(path, key), [&] { return Expression::parse(text, o); });
}

std::shared_ptr<const Surface> parseSurface(const json& v, const std::string& path, const std::string& defName) {
  expectObject(v, path);
  const std::string type = string(member(v, path, "type"), child(path, "type"));
  const std::string name = v.contains("name") ? string(v["name"], child(path, "name")) : defName;
  auto dom = [&](const Box2& def) { return v.contains("domain") ? box(v["domain"], child(path, "domain")) : def; };
  const double twoPi = 6.283185307179586;
  return withPath(path, [&]() -> std::shared_ptr<const Surface> {
    if (type == "expression") {
      checkKeys(v, path, {"type", "name", "x", "y", "z", "domain"});
      return std::make_shared<ExpressionSurface>(formula(v, path, "x", "x(u,v)"), formula(v, path, "y", "y(u,v)"),
                                                 formula(v, path, "z", "z(u,v)"),
                                                 box(member(v, path, "domain"), child(path, "domain")), name);
    }
    if (type == "heightfield") {
      checkKeys(v, path, {"type", "name", "z", "domain"});
      return std::make_shared<HeightFieldSurface>(formula(v, path, "z", "z(u,v)"),
                                                  box(member(v, path, "domain"), child(path, "domain")), name);
    }
    if (type == "p2") {
      checkKeys(v, path, {"type", "name", "domain"});
      return paperP2(dom({{-10, -10}, {10, 10}}));
    }
    Vec3 center = v.contains("center") ? point3(v["center"], child(path, "center")) : Vec3::Zero();
    if (type == "plane") {
      checkKeys(v, path, {"type", "name", "origin", "a1", "a2", "domain"});
      return std::make_shared<PlaneSurface>(
          v.contains("origin") ? point3(v["origin"], child(path, "origin")) : Vec3::Zero(),
          v.contains("a1") ? point3(v["a1"], child(path, "a1")) : Vec3::UnitX(),
          v.contains("a2") ? point3(v["a2"], child(path, "a2")) : Vec3::UnitY(), dom({{0, 0}, {1, 1}}));
    }
    if (type == "sphere") {
      checkKeys(v, path, {"type", "name", "radius", "center", "domain"});
      return std::make_shared<SphereSurface>(positive(member(v, path, "radius"), child(path, "radius")), center,
                                             dom({{0.0, -1.4}, {twoPi, 1.4}}));
    }
    if (type == "cylinder") {
      checkKeys(v, path, {"type", "name", "radius", "center", "domain"});
      return std::make_shared<CylinderSurface>(positive(member(v, path, "radius"), child(path, "radius")), center,
                                               dom({{0.0, 0.0}, {twoPi, 1.0}}));
    }
    if (type == "torus") {
      checkKeys(v, path, {"type", "name", "majorRadius", "minorRadius", "center", "domain"});
      const double R = positive(member(v, path, "majorRadius"), child(path, "majorRadius"));
      const double r = positive(member(v, path, "minorRadius"), child(path, "minorRadius"));
      require(r < R, ErrorCode::InvalidArgument, child(path, "minorRadius") + ": must be below majorRadius");
      return std::make_shared<TorusSurface>(R, r, center, dom({{0.0, 0.0}, {twoPi, twoPi}}));
    }
    if (type == "bezier") {
      checkKeys(v, path, {"type", "name", "points"});
      const json& p = member(v, path, "points");
      const std::string pp = child(path, "points");
      if (!p.is_array() || p.size() != 4) fail(pp, "expected 4 rows of 4 control points [x, y, z]");
      std::array<std::array<Vec3, 4>, 4> cp;
      for (size_t i = 0; i < 4; ++i) {
        if (!p[i].is_array() || p[i].size() != 4) fail(index(pp, i), "expected 4 control points [x, y, z]");
        for (size_t j = 0; j < 4; ++j) cp[i][j] = point3(p[i][j], index(index(pp, i), j));
      }
      return std::make_shared<BezierPatchSurface>(cp, name);
    }
    fail(child(path, "type"), "unknown surface type '" + type +
                                  "' (expected expression, heightfield, plane, sphere, cylinder, torus, bezier or p2)");
  });
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

SurfaceCaseSpec parseSurfaceCaseJson(const std::string& text) { return parseSurfaceCaseJsonTree(parseText(text)); }

SurfaceCaseSpec parseSurfaceCaseJsonTree(const json& root) {
  expectObject(root, "");
  checkKeys(root, "",
            {"name", "description", "metric", "adaptation", "options", "boundary", "surfaces", "patches", "shared",
             "sources3d"});
  SurfaceCaseSpec spec;
  SurfaceMeshOptions& o = spec.options;
  if (root.contains("metric")) {
    const json& m = root["metric"];
    expectObject(m, "metric");
    checkKeys(m, "metric",
              {"chordTolerance", "chordSafety", "angleTolerance", "hmin", "hmax", "maxAspectRatio", "gradation",
               "contourCurvature"});
    if (m.contains("contourCurvature")) o.contourCurvature = boolean(m["contourCurvature"], "metric.contourCurvature");
    o.chordSafety = m.contains("chordSafety") ? number(m["chordSafety"], "metric.chordSafety") : kDefaultChordSafety;
    require(std::isfinite(o.chordSafety) && o.chordSafety > 0.0, ErrorCode::InvalidArgument,
            "metric.chordSafety: must be > 0");
    o.metric.chordTolerance = numberOr(m, "metric", "chordTolerance", o.metric.chordTolerance);
    o.metric.angleTolerance = numberOr(m, "metric", "angleTolerance", o.metric.angleTolerance);
    o.metric.hmin = positiveOr(m, "metric", "hmin", o.metric.hmin);
    o.metric.hmax = positiveOr(m, "metric", "hmax", o.metric.hmax);
    o.metric.maxAspectRatio = positiveOr(m, "metric", "maxAspectRatio", o.metric.maxAspectRatio);
    if (m.contains("gradation")) {
      o.gradation = m["gradation"].is_null() ? 0.0 : number(m["gradation"], "metric.gradation");
      require(o.gradation == 0.0 || o.gradation >= 1.0, ErrorCode::InvalidArgument,
              "metric.gradation: must be >= 1 (or null: off)");
    }
    withPath("metric", [&] { validate(o.metric); });
  }
  if (root.contains("adaptation")) o.adaptation = boolean(root["adaptation"], "adaptation");
  if (root.contains("boundary")) o.boundary = parseBoundaryRules(root["boundary"], "boundary", false);
  if (root.contains("options")) {
    const json& v = root["options"];
    expectObject(v, "options");
    checkKeys(v, "options", {"maxElements", "maxRounds", "improvementPasses", "quads", "allQuads", "parameterization"});
    if (v.contains("parameterization")) {
      const std::string s = string(v["parameterization"], "options.parameterization");
      if (s == "folded")
        o.parameterization = ParameterizationStorage::Folded;
      else if (s == "stored")
        o.parameterization = ParameterizationStorage::Stored;
      else if (s == "computed")
        o.parameterization = ParameterizationStorage::Computed;
      else
        fail("options.parameterization", "expected \"folded\", \"stored\" or \"computed\", got \"" + s + "\"");
    }
    if (v.contains("quads")) o.quads = boolean(v["quads"], "options.quads");
    if (v.contains("allQuads")) o.allQuads = boolean(v["allQuads"], "options.allQuads");
    if (v.contains("maxElements")) {
      o.mesher.maxElements = integer(v["maxElements"], "options.maxElements");
      require(o.mesher.maxElements > 0, ErrorCode::InvalidArgument, "options.maxElements: must be positive");
    }
    if (v.contains("maxRounds")) {
      o.maxRounds = integer(v["maxRounds"], "options.maxRounds");
      require(o.maxRounds >= 1, ErrorCode::InvalidArgument, "options.maxRounds: must be >= 1");
    }
    if (v.contains("improvementPasses")) {
      o.mesher.improvementPasses = integer(v["improvementPasses"], "options.improvementPasses");
      require(o.mesher.improvementPasses >= 0, ErrorCode::InvalidArgument, "options.improvementPasses: must be >= 0");
    }
  }
  std::map<std::string, std::shared_ptr<const Surface>> named;
  if (root.contains("surfaces")) {
    expectObject(root["surfaces"], "surfaces");
    for (auto it = root["surfaces"].begin(); it != root["surfaces"].end(); ++it)
      named[it.key()] = parseSurface(it.value(), child("surfaces", it.key()), it.key());
  }
  const json& patches = member(root, "", "patches");
  if (!patches.is_array() || patches.empty()) fail("patches", "expected a non-empty array of patches");
  std::map<std::string, int> patchIndex;
  for (size_t i = 0; i < patches.size(); ++i) {
    const std::string path = index("patches", i);
    const json& v = patches[i];
    expectObject(v, path);
    checkKeys(v, path, {"name", "id", "surface", "outer", "holes", "sources"});
    SurfacePatch p;
    p.name = v.contains("name") ? string(v["name"], child(path, "name")) : std::to_string(i);
    p.id = v.contains("id") ? integer(v["id"], child(path, "id")) : int(i) + 1;
    const json& s = member(v, path, "surface");
    if (s.is_string()) {
      auto it = named.find(s.get<std::string>());
      if (it == named.end())
        fail(child(path, "surface"), "no surface named '" + s.get<std::string>() + "' in surfaces");
      p.surface = it->second;
    } else {
      p.surface = parseSurface(s, child(path, "surface"), p.name);
    }
    p.domain.outer = v.contains("outer") ? parseContour(v["outer"], child(path, "outer"), 1, "[u, v]")
                                         : rectangle(p.surface->domain());
    if (v.contains("holes")) {
      const json& h = v["holes"];
      if (!h.is_array()) fail(child(path, "holes"), "expected an array of contours");
      for (size_t k = 0; k < h.size(); ++k)
        p.domain.holes.push_back(parseContour(h[k], index(child(path, "holes"), k), int(k) + 2, "[u, v]"));
    }
    if (v.contains("sources")) {
      const json& ss = v["sources"];
      if (!ss.is_array()) fail(child(path, "sources"), "expected an array of sources");
      std::vector<SourceSpec> sources;
      for (size_t k = 0; k < ss.size(); ++k)
        sources.push_back(
            parseSource(ss[k], index(child(path, "sources"), k),
                        {SourceType::Radial, SourceType::Segment, SourceType::Polyline, SourceType::Curve}));
      p.sources = discreteSources(sources);
    }
    if (patchIndex.count(p.name)) fail(child(path, "name"), "duplicate patch name '" + p.name + "'");
    patchIndex[p.name] = int(i);
    spec.model.patches.push_back(std::move(p));
  }
  if (root.contains("shared")) {
    const json& sh = root["shared"];
    if (!sh.is_array()) fail("shared", "expected an array");
    for (size_t i = 0; i < sh.size(); ++i) {
      const std::string path = index("shared", i);
      expectObject(sh[i], path);
      checkKeys(sh[i], path, {"a", "b", "reversed"});
      auto ref = [&](const char* key) {
        const std::string rp = child(path, key);
        const json& r = member(sh[i], path, key);
        expectObject(r, rp);
        checkKeys(r, rp, {"patch", "contour", "curve"});
        CurveRef c;
        const json& pj = member(r, rp, "patch");
        if (pj.is_string()) {
          auto it = patchIndex.find(pj.get<std::string>());
          if (it == patchIndex.end()) fail(child(rp, "patch"), "no patch named '" + pj.get<std::string>() + "'");
          c.patch = it->second;
        } else {
          c.patch = integer(pj, child(rp, "patch"));
          if (c.patch < 0 || c.patch >= int(spec.model.patches.size())) fail(child(rp, "patch"), "no such patch");
        }
        c.contour = r.contains("contour") ? integer(r["contour"], child(rp, "contour")) : 0;
        c.curve = integer(member(r, rp, "curve"), child(rp, "curve"));
        const SurfacePatch& p = spec.model.patches[size_t(c.patch)];
        if (c.contour < 0 || c.contour > int(p.domain.holes.size())) fail(child(rp, "contour"), "no such contour");
        const Contour& ct = c.contour == 0 ? p.domain.outer : p.domain.holes[size_t(c.contour - 1)];
        if (c.curve < 0 || c.curve >= int(ct.curves.size())) fail(child(rp, "curve"), "no such curve");
        return c;
      };
      SharedCurve s{ref("a"), ref("b"), false};
      if (sh[i].contains("reversed")) {
        s.reversed = boolean(sh[i]["reversed"], child(path, "reversed"));
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
      const std::string path = index("sources3d", i);
      expectObject(ss[i], path);
      checkKeys(ss[i], path, {"type", "center", "h", "radius"});
      if (ss[i].contains("type") && string(ss[i]["type"], child(path, "type")) != "radial")
        fail(child(path, "type"), "only 'radial' 3D sources are supported");
      Source3D s;
      s.center = point3(member(ss[i], path, "center"), child(path, "center"));
      s.h = positive(member(ss[i], path, "h"), child(path, "h"));
      s.radius = number(member(ss[i], path, "radius"), child(path, "radius"));
      require(s.radius >= 0, ErrorCode::InvalidArgument, child(path, "radius") + ": must be >= 0");
      spec.model.sources3d.push_back(s);
    }
  }
  return spec;
}

}  // namespace anisomesh

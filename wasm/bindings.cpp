// The one embind bindings file: exposes the anisomesh core to JavaScript.
//
// Convention: every function returns a plain JS object. On success it carries the
// result fields; on failure { error: CODE, message }. The JS wrapper (api.js) turns
// the latter into an AnisomeshError, so no C++ exception ever crosses the boundary
// and the module stays usable after bad input.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cmath>
#include <exception>
#include <string>

#include "anisomesh/anisomesh.h"

using emscripten::val;
using namespace anisomesh;

namespace {

// Runs f, turning core errors into { error, message } objects.
template <class F>
val guarded(F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    val out = val::object();
    out.set("error", std::string(errorCodeName(e.code())));
    out.set("message", std::string(e.what()));
    return out;
  } catch (const std::exception& e) {
    val out = val::object();
    out.set("error", std::string("INTERNAL"));
    out.set("message", std::string(e.what()));
    return out;
  }
}

double number(const val& obj, const char* key) {
  const val v = obj[key];
  if (!v.isNumber()) throw Error(ErrorCode::InvalidArgument, std::string("metric field '") + key + "' must be a number");
  return v.as<double>();
}

// A metric from a plain JS object: { m11, m12, m22 } or { alpha, h1, h2 } (or { h }).
Metric metricFromJs(const val& m) {
  if (!m.hasOwnProperty("m11") && !m.hasOwnProperty("h1") && !m.hasOwnProperty("h"))
    throw Error(ErrorCode::InvalidArgument, "a metric needs either {m11, m12, m22}, {alpha, h1, h2} or {h}");
  if (m.hasOwnProperty("m11")) return Metric::fromTensor(number(m, "m11"), number(m, "m12"), number(m, "m22"));
  if (m.hasOwnProperty("h1"))
    return Metric::fromSizes(m.hasOwnProperty("alpha") ? number(m, "alpha") : 0.0, number(m, "h1"), number(m, "h2"));
  return Metric::isotropic(number(m, "h"));
}

val metricToJs(const Metric& m) {
  const Mat2 t = m.tensor();
  const Mat2& mt = m.transform();
  const MetricSizes s = m.sizes();
  val out = val::object();
  out.set("m11", t(0, 0));
  out.set("m12", t(0, 1));
  out.set("m22", t(1, 1));
  out.set("t11", mt(0, 0));
  out.set("t12", mt(0, 1));
  out.set("t22", mt(1, 1));
  out.set("alpha", s.alpha);
  out.set("h1", s.h1);
  out.set("h2", s.h2);
  return out;
}

val metricCreate(val m) {
  return guarded([&] { return metricToJs(metricFromJs(m)); });
}

val metricIntersect(val a, val b) {
  return guarded([&] { return metricToJs(intersect(metricFromJs(a), metricFromJs(b))); });
}

val metricInterpolate(val a, val b, double t) {
  return guarded([&] {
    require(std::isfinite(t) && t >= 0.0 && t <= 1.0, ErrorCode::InvalidArgument,
            "interpolation parameter t must be in [0, 1], got " + std::to_string(t));
    return metricToJs(interpolate(metricFromJs(a), metricFromJs(b), t));
  });
}

val metricLength(val m, double dx, double dy) {
  return guarded([&] {
    require(std::isfinite(dx) && std::isfinite(dy), ErrorCode::InvalidArgument, "vector components must be finite");
    val out = val::object();
    out.set("length", metricFromJs(m).length(Vec2(dx, dy)));
    return out;
  });
}

val metricDifference(val a, val b) {
  return guarded([&] {
    val out = val::object();
    out.set("difference", difference(metricFromJs(a), metricFromJs(b)));
    return out;
  });
}

// Points of the unit ball boundary {x : |Mt (x - c)| = 1}, as a closed polyline
// (segments points, xy interleaved), for drawing.
val metricEllipse(val m, double cx, double cy, int segments) {
  return guarded([&] {
    require(segments >= 3 && segments <= 100000, ErrorCode::InvalidArgument, "ellipse segments must be in [3, 100000]");
    const Mat2 inv = metricFromJs(m).transform().inverse();
    std::vector<double> xy(2 * static_cast<size_t>(segments));
    for (int i = 0; i < segments; ++i) {
      const double a = 2.0 * M_PI * i / segments;
      const Vec2 p = Vec2(cx, cy) + inv * Vec2(std::cos(a), std::sin(a));
      xy[2 * i] = p.x();
      xy[2 * i + 1] = p.y();
    }
    val out = val::object();
    // Copy out of the heap: the view would be detached by memory growth.
    out.set("points", val(emscripten::typed_memory_view(xy.size(), xy.data())).call<val>("slice"));
    return out;
  });
}

std::string version() { return "0.1.0"; }

}  // namespace

EMSCRIPTEN_BINDINGS(anisomesh) {
  emscripten::function("version", &version);
  emscripten::function("metricCreate", &metricCreate);
  emscripten::function("metricIntersect", &metricIntersect);
  emscripten::function("metricInterpolate", &metricInterpolate);
  emscripten::function("metricLength", &metricLength);
  emscripten::function("metricDifference", &metricDifference);
  emscripten::function("metricEllipse", &metricEllipse);
}

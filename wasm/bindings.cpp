// The one embind bindings file: exposes the anisomesh core to JavaScript.
//
// Convention: every function returns a plain JS object. On success it carries the
// result fields; on failure { error: CODE, message }. The JS wrapper (api.js) turns
// the latter into an AnisomeshError, so no C++ exception ever crosses the boundary
// and the module stays usable after bad input.
#include <emscripten.h>
#include <emscripten/bind.h>
#include <emscripten/val.h>
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "anisomesh/anisomesh.h"
#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/core/version.h"
#include "anisomesh/geometry/expression.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/case_svg.h"
#include "anisomesh/io/case_vtu.h"
#include "anisomesh/io/control_space_export.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/mesh_formats.h"
#include "anisomesh/io/report_json.h"
#include "anisomesh/io/run_case.h"
#include "anisomesh/io/svg.h"
#include "anisomesh/io/svg_import.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/metric/metric_ellipse.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/input_size_metrics.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "anisomesh/pipeline/pipeline.h"

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
  } catch (const std::bad_alloc&) {
    // The run's memory is released by the unwinding: the module stays usable.
    val out = val::object();
    out.set("error", std::string("OUT_OF_MEMORY"));
    out.set("message", std::string("out of memory"));
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
  if (!v.isNumber())
    throw Error(ErrorCode::InvalidArgument, std::string("metric field '") + key + "' must be a number");
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
val metricEllipseJs(val m, double cx, double cy, int segments) {
  return guarded([&] {
    const std::vector<Vec2> pts = anisomesh::metricEllipse(metricFromJs(m), Vec2(cx, cy), segments);
    std::vector<double> xy;
    xy.reserve(2 * pts.size());
    for (const Vec2& p : pts) xy.insert(xy.end(), {p.x(), p.y()});
    val out = val::object();
    // Copy out of the heap: the view would be detached by memory growth.
    out.set("points", val(emscripten::typed_memory_view(xy.size(), xy.data())).call<val>("slice"));
    return out;
  });
}

// Copies n values out of the wasm heap into a new JS typed array (a view would be
// detached by the next memory growth).
template <class T>
val typedCopy(const T* data, size_t n) {
  return val(emscripten::typed_memory_view(n, data)).call<val>("slice");
}

template <class T>
std::vector<T> numbers(const val& obj, const char* key) {
  const val v = obj[key];
  if (v.isUndefined() || v.isNull()) return {};
  return emscripten::convertJSArrayToNumberVector<T>(v);
}

// A text argument: a JS string (embind's conversion, a JS loop over its characters) or a
// Uint8Array of its UTF-8 bytes, copied by one TypedArray.set (api.js encodes large texts with
// TextEncoder: 1.5 s of embind conversion for the 245 MB of a 2M-triangle .mesh + .sol).
std::string textOf(const val& text) {
  if (text.isString()) return text.as<std::string>();
  std::string s(text["length"].as<size_t>(), '\0');
  val(emscripten::typed_memory_view(s.size(), reinterpret_cast<unsigned char*>(s.data()))).call<void>("set", text);
  return s;
}

// A text out of the heap as a JS string: large ones decoded by TextDecoder in one pass (embind's
// std::string conversion scans the bytes twice in JS loops, for NULs and for the end: 13 ms of a
// 4 MB .mesh text); small ones, or where there is no TextDecoder, by embind.
val textToJs(const std::string& text) {
  static const val decoder =
      val::global("TextDecoder").isUndefined() ? val::undefined() : val::global("TextDecoder").new_();
  if (text.size() < (1u << 12) || decoder.isUndefined()) return val(text);
  return decoder.call<val>(
      "decode", emscripten::typed_memory_view(text.size(), reinterpret_cast<const unsigned char*>(text.data())));
}

// The mesh as typed arrays: vertices (dimension values each), params (uv), positions
// (Float32 xyz for WebGL), connectivity (Uint32, 0-based) and references (Int32).
val meshToJs(const Mesh& mesh) {
  const size_t n = mesh.points.size();
  std::vector<double> vertices(static_cast<size_t>(mesh.dimension) * n), params(2 * n);
  std::vector<float> positions(3 * n);
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < mesh.dimension; ++k) vertices[mesh.dimension * i + k] = mesh.points[i][k];
    const Vec2 uv = mesh.params.size() == n ? mesh.params[i] : Vec2(mesh.points[i].head<2>());
    params[2 * i] = uv.x();
    params[2 * i + 1] = uv.y();
    for (int k = 0; k < 3; ++k) positions[3 * i + k] = static_cast<float>(mesh.points[i][k]);
  }
  auto flat = [](const auto& cells) {
    std::vector<std::uint32_t> out;
    out.reserve(cells.size() * (cells.empty() ? 0 : cells[0].size()));
    for (const auto& c : cells)
      for (int v : c) out.push_back(static_cast<std::uint32_t>(v));
    return out;
  };
  const auto tris = flat(mesh.triangles), quads = flat(mesh.quads), edges = flat(mesh.edges);
  std::vector<std::int32_t> vertexRefs(mesh.pointRefs.begin(), mesh.pointRefs.end());
  vertexRefs.resize(n, 0);
  val out = val::object();
  out.set("dimension", mesh.dimension);
  out.set("vertices", typedCopy(vertices.data(), vertices.size()));
  out.set("params", typedCopy(params.data(), params.size()));
  out.set("positions", typedCopy(positions.data(), positions.size()));
  out.set("triangles", typedCopy(tris.data(), tris.size()));
  out.set("quads", typedCopy(quads.data(), quads.size()));
  out.set("edges", typedCopy(edges.data(), edges.size()));
  out.set("vertexRefs", typedCopy(vertexRefs.data(), vertexRefs.size()));
  out.set("triangleRefs", typedCopy(mesh.triangleRefs.data(), mesh.triangleRefs.size()));
  out.set("quadRefs", typedCopy(mesh.quadRefs.data(), mesh.quadRefs.size()));
  out.set("edgeRefs", typedCopy(mesh.edgeRefs.data(), mesh.edgeRefs.size()));
  return out;
}

// The inverse of meshToJs (the wrapper has checked the shapes).
Mesh meshFromJs(const val& js) {
  Mesh mesh;
  mesh.dimension = js["dimension"].as<int>();
  const auto v = numbers<double>(js, "vertices");
  const size_t n = v.size() / mesh.dimension;
  mesh.points.reserve(n);
  for (size_t i = 0; i < n; ++i)
    mesh.points.emplace_back(v[mesh.dimension * i], v[mesh.dimension * i + 1],
                             mesh.dimension == 3 ? v[mesh.dimension * i + 2] : 0.0);
  const auto params = numbers<double>(js, "params");
  if (params.size() == 2 * n)
    for (size_t i = 0; i < n; ++i) mesh.params.emplace_back(params[2 * i], params[2 * i + 1]);
  auto cells = [&](const char* key, auto& into) {
    const auto c = numbers<std::uint32_t>(js, key);
    const size_t k = std::tuple_size<typename std::decay_t<decltype(into)>::value_type>::value;
    into.reserve(c.size() / k);
    for (size_t i = 0; i + k <= c.size(); i += k) {
      typename std::decay_t<decltype(into)>::value_type cell;
      for (size_t j = 0; j < k; ++j) {
        // The message only for the bad index: formatting it for every index took 40 % of a
        // 1e6-triangle remesh call (3.6 s of 8.9 s under the profiler).
        if (!(c[i + j] < n))
          throw Error(ErrorCode::InvalidArgument, std::string(key) + ": vertex index " + std::to_string(c[i + j]) +
                                                      " out of range (" + std::to_string(n) + " vertices)");
        cell[j] = static_cast<int>(c[i + j]);
      }
      into.push_back(cell);
    }
  };
  cells("triangles", mesh.triangles);
  cells("quads", mesh.quads);
  cells("edges", mesh.edges);
  auto refs = [&](const char* key, std::vector<int>& into, size_t count) {
    into = numbers<int>(js, key);
    into.resize(count, 0);
  };
  refs("vertexRefs", mesh.pointRefs, n);
  refs("triangleRefs", mesh.triangleRefs, mesh.triangles.size());
  refs("quadRefs", mesh.quadRefs, mesh.quads.size());
  refs("edgeRefs", mesh.edgeRefs, mesh.edges.size());
  return mesh;
}

MeshFormat formatFromName(const std::string& name) {
  if (name == "mesh" || name == "medit") return MeshFormat::Medit;
  if (name == "vtk") return MeshFormat::Vtk;
  if (name == "obj") return MeshFormat::Obj;
  if (name == "msh") return MeshFormat::Gmsh;
  if (name == "msh2") return MeshFormat::Gmsh22;
  if (name == "meshb") return MeshFormat::MeditBinary;
  throw Error(ErrorCode::InvalidArgument,
              "unknown mesh format '" + name + "' (expected mesh, meshb, vtk, obj, msh or msh2)");
}

// Per-edge metric lengths, per-element metric qualities (triangles, then quads) and the
// smallest requested size per vertex, as the quality report measures them (for the
// colouring, the histograms and the lifted 3D view), with the distinct edges; without a
// control space (surface runs) only the edges.
val meshMeasures(const Mesh& mesh, const ControlSpace* cs) {
  ElementMeasures items;
  if (cs)
    measureQuality(mesh, *cs, &items);
  else
    items.edges = distinctElementEdges(mesh);
  std::vector<std::uint32_t> edges(2 * items.edges.size());
  for (size_t e = 0; e < items.edges.size(); ++e) {
    edges[2 * e] = std::uint32_t(items.edges[e][0]);
    edges[2 * e + 1] = std::uint32_t(items.edges[e][1]);
  }
  auto asFloat = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
  val out = val::object();
  out.set("edges", typedCopy(edges.data(), edges.size()));
  if (cs) {
    const std::vector<float> edgeLength = asFloat(items.edgeLength), quality = asFloat(items.quality),
                             vertexH = asFloat(items.vertexMinSize);
    out.set("edgeLength", typedCopy(edgeLength.data(), edgeLength.size()));
    out.set("quality", typedCopy(quality.data(), quality.size()));
    out.set("vertexH", typedCopy(vertexH.data(), vertexH.size()));
  }
  return out;
}

// Surface control-space glyphs (ellipses of the final per-patch control spaces) as flat
// arrays: patch per glyph, offsets (glyph g has points offsets[g] .. offsets[g + 1]),
// uv (2 per point) and xyz (3 per point, Float32 for WebGL).
val glyphsToJs(const std::vector<ControlSpaceGlyph>& glyphs) {
  std::vector<int> patch, offsets{0};
  std::vector<double> uv;
  std::vector<float> xyz;
  for (const ControlSpaceGlyph& g : glyphs) {
    patch.push_back(g.patch);
    for (size_t k = 0; k < g.uv.size(); ++k) {
      uv.insert(uv.end(), {g.uv[k].x(), g.uv[k].y()});
      const Vec3 x = k < g.xyz.size() ? g.xyz[k] : Vec3::Zero();
      xyz.insert(xyz.end(), {float(x.x()), float(x.y()), float(x.z())});
    }
    offsets.push_back(int(uv.size() / 2));
  }
  val out = val::object();
  out.set("patch", typedCopy(patch.data(), patch.size()));
  out.set("offsets", typedCopy(offsets.data(), offsets.size()));
  out.set("uv", typedCopy(uv.data(), uv.size()));
  out.set("xyz", typedCopy(xyz.data(), xyz.size()));
  return out;
}

// Surface runs: the 3D quality of each element and the 3D metric length of each edge (in
// the order of distinctElementEdges) into measures m, when measured.
void setSurfaceMeasures(val& m, const Mesh& mesh, const std::vector<double>& elementQuality,
                        const std::vector<SurfaceEdgeLength>& edgeLengths) {
  if (!elementQuality.empty()) {
    const std::vector<float> quality(elementQuality.begin(), elementQuality.end());
    m.set("quality", typedCopy(quality.data(), quality.size()));
  }
  if (!edgeLengths.empty()) {
    std::map<std::pair<int, int>, double> byEdge;
    for (const SurfaceEdgeLength& e : edgeLengths) byEdge[{e.a, e.b}] = e.length;
    const std::vector<std::array<int, 2>> edges = distinctElementEdges(mesh);
    std::vector<float> lengths(edges.size(), 0.0f);
    for (size_t k = 0; k < edges.size(); ++k) {
      const auto it = byEdge.find({std::min(edges[k][0], edges[k][1]), std::max(edges[k][0], edges[k][1])});
      if (it != byEdge.end()) lengths[k] = float(it->second);
    }
    m.set("edgeLength", typedCopy(lengths.data(), lengths.size()));
  }
}

// A run made with stats: false, kept for its quality report (a surface run: with its 3D
// measures, chord deviations and the rest), which the caller asks for after it has drawn
// the mesh. meshCase returns one per such run; the JS wrapper owns
// it (report() or dispose() deletes it), so runs are independent of each other.
class CaseReportHandle {
 public:
  explicit CaseReportHandle(CaseRun run) : run_(std::move(run)) {}
  // Surface runs made with elementMeasures: false: { quality, edgeLength } (as measures has
  // them), measured now; the run stays kept for stats().
  val elementMeasures() {
    return guarded([&] {
      require(run_.surfaceReport != nullptr, ErrorCode::InvalidArgument,
              "elementMeasures: not a surface run kept for its report");
      measureSurfaceElements(*run_.surfaceReport);
      val m = val::object();
      setSurfaceMeasures(m, run_.mesh, run_.surfaceReport->elementQuality, run_.surfaceReport->edgeLengths);
      return m;
    });
  }
  // The quality report (stats JSON text) of the kept run; the run is freed after it.
  val stats() {
    return guarded([&] {
      require(run_.finalSpace != nullptr || run_.surfaceReport != nullptr, ErrorCode::InvalidArgument,
              "report: this run's report was already made");
      const double t0 = emscripten_get_now();
      nlohmann::json stats = caseRunStats(run_);
      val out = val::object();
      out.set("stats", textToJs(stats.dump()));
      out.set("statsMs", emscripten_get_now() - t0);
      run_ = CaseRun();
      return out;
    });
  }

 private:
  CaseRun run_;
};

// A whole JSON case (planar or surface): { mesh, stats (JSON text, or null with stats:
// false), controlSpace (JSON text or null), vertexMetrics, measures, timings }.
// options: { inspectControlSpace, vertexMetrics, measures, stats, quads, allQuads,
// maxElements, controlSpaceUpdates, onProgress(fraction) -> false to cancel }.
// options.svg ({ uv, azimuth, elevation } in radians, or true): the run's .svg picture.
bool wantsSvg(const val& options) {
  return options["svg"].isTrue() || options["svg"].typeOf().as<std::string>() == "object";
}

CaseSvgOptions svgOptions(const val& options) {
  CaseSvgOptions o;
  const val svg = options["svg"];
  if (svg.typeOf().as<std::string>() != "object") return o;
  o.uv = svg["uv"].isTrue();
  if (svg["azimuth"].isNumber()) o.azimuth = svg["azimuth"].as<double>();
  if (svg["elevation"].isNumber()) o.elevation = svg["elevation"].as<double>();
  return o;
}

val meshCaseJson(std::string jsonText, val options) {
  return guarded([&] {
    const double t0 = emscripten_get_now();
    RunCaseOptions o;
    o.inspectControlSpace = options["inspectControlSpace"].isTrue();
    o.vertexMetrics = options["vertexMetrics"].isTrue();
    o.stats = !options["stats"].isFalse();
    const bool measures = options["measures"].isTrue();
    // Surface, stats false: the per-element values now (unless elementMeasures: false), the rest in report().
    o.elementMeasures = measures && !options["elementMeasures"].isFalse();
    if (options["quads"].isTrue() || options["quads"].isFalse()) o.quads = options["quads"].isTrue();
    if (options["allQuads"].isTrue() || options["allQuads"].isFalse()) o.allQuads = options["allQuads"].isTrue();
    if (options["maxElements"].isNumber())
      o.maxElements = static_cast<std::int64_t>(options["maxElements"].as<double>());
    if (options["controlSpaceUpdates"].isFalse()) o.controlSpaceUpdates = false;
    o.controlSpaceGlyphs =
        options["controlSpaceGlyphs"].isTrue() || (wantsSvg(options) && options["svg"]["controlSpace"].isTrue());
    o.patchParams = options["patchParams"].isTrue();
    const val onProgress = options["onProgress"];
    if (onProgress.typeOf().as<std::string>() == "function")
      o.progress = [onProgress](double fraction) { return !onProgress(fraction).isFalse(); };
    CaseRun run = runCase(jsonText, o);
    const double t1 = emscripten_get_now();
    val out = val::object();
    out.set("mesh", meshToJs(run.mesh));
    if (wantsSvg(options)) out.set("svg", textToJs(caseRunSvg(run, svgOptions(options))));
    if (options["vtu"].isTrue()) out.set("vtu", textToJs(caseRunVtu(run)));
    out.set("stats", run.stats.is_null() ? val::null() : textToJs(run.stats.dump()));
    out.set("controlSpace",
            o.inspectControlSpace && !run.controlSpace.is_null() ? textToJs(run.controlSpace.dump()) : val::null());
    out.set("vertexMetrics",
            run.vertexMetrics.empty() ? val::null() : typedCopy(run.vertexMetrics.data(), run.vertexMetrics.size()));
    const double t2 = emscripten_get_now();
    if (measures) {
      val m = meshMeasures(run.mesh, run.finalSpace.get());
      setSurfaceMeasures(m, run.mesh, run.elementQuality, run.edgeLengths);
      out.set("measures", m);
    }
    if (o.controlSpaceGlyphs) out.set("glyphs", glyphsToJs(run.glyphs));
    if (o.patchParams) {
      std::vector<double> corners(2 * run.cornerParams.size());
      for (size_t i = 0; i < run.cornerParams.size(); ++i) {
        corners[2 * i] = run.cornerParams[i].x();
        corners[2 * i + 1] = run.cornerParams[i].y();
      }
      out.set("elementPatch", typedCopy(run.elementPatch.data(), run.elementPatch.size()));
      out.set("cornerParams", typedCopy(corners.data(), corners.size()));
    }
    const double t3 = emscripten_get_now();
    // Milliseconds: the case run (parse, control space, section 3.2 rounds, meshing, and
    // the report unless deferred), copying the results out, the measures.
    val timings = val::object();
    timings.set("runMs", t1 - t0);
    timings.set("outputMs", t2 - t1);
    timings.set("measuresMs", t3 - t2);
    out.set("timings", timings);
    if (run.stats.is_null()) {
      run.controlSpace = nullptr;
      run.vertexMetrics.clear();
      out.set("report", val(std::make_shared<CaseReportHandle>(std::move(run))));
    }
    return out;
  });
}

val writeMeshText(val mesh, std::string format) {
  return guarded([&] {
    val out = val::object();
    if (format == "svg") {
      out.set("text", textToJs(writeSvg(meshFromJs(mesh))));
    } else if (formatFromName(format) == MeshFormat::MeditBinary) {  // bytes: a Uint8Array copy
      const std::string bytes = writeMeshString(meshFromJs(mesh), MeshFormat::MeditBinary);
      out.set("bytes", val::global("Uint8Array")
                           .new_(emscripten::typed_memory_view(bytes.size(),
                                                               reinterpret_cast<const unsigned char*>(bytes.data()))));
    } else {
      out.set("text", textToJs(writeMeshString(meshFromJs(mesh), formatFromName(format))));
    }
    return out;
  });
}

val readMeshText(val text, std::string format) {
  return guarded([&] {
    val out = val::object();
    out.set("mesh", meshToJs(parseMeshString(textOf(text), formatFromName(format))));
    return out;
  });
}

// A .sol as per-vertex tensors (m11, m12, m22 each), validated as metrics.
val readSolText(val text, int vertexCount) {
  return guarded([&] {
    const SolData sol = parseSol(textOf(text));
    const std::vector<Metric> metrics = solToMetrics(sol, vertexCount);  // checks every value
    // Tensors as written (not Metric::tensor(), whose square root round trip moves the last
    // bits): remesh(mesh, readSol(...)) then builds the very metrics the CLI builds from the file.
    std::vector<double> m;
    if (sol.type == 3) {
      m = sol.values;
    } else {
      m.reserve(3 * metrics.size());
      for (const Metric& x : metrics) {
        const Mat2 t = x.tensor();
        m.insert(m.end(), {t(0, 0), t(0, 1), t(1, 1)});
      }
    }
    val out = val::object();
    out.set("metrics", typedCopy(m.data(), m.size()));
    return out;
  });
}

std::vector<Metric> metricsFromFlat(const std::vector<double>& m) {
  std::vector<Metric> metrics;
  metrics.reserve(m.size() / 3);
  for (size_t i = 0; i + 3 <= m.size(); i += 3) metrics.push_back(Metric::fromTensor(m[i], m[i + 1], m[i + 2]));
  return metrics;
}

val writeSolText(val metrics) {
  return guarded([&] {
    val out = val::object();
    out.set(
        "text",
        textToJs(writeSol(metricsToSol(metricsFromFlat(emscripten::convertJSArrayToNumberVector<double>(metrics))))));
    return out;
  });
}

// Remeshing of a mesh under per-vertex tensors: { mesh, stats }.
val remeshJs(val mesh, val metrics, val options) {
  return guarded([&] {
    Mesh input = meshFromJs(mesh);
    // metrics null: isotropic sizes from the mesh itself (options.hsiz everywhere, else
    // each vertex's mean incident edge length), as the CLI does without -sol.
    const double hsiz = options["hsiz"].isNumber() ? options["hsiz"].as<double>() : 0.0;
    std::vector<Metric> m = !metrics.isNull()
                                ? metricsFromFlat(emscripten::convertJSArrayToNumberVector<double>(metrics))
                            : hsiz > 0 ? uniformMetrics(input, hsiz)
                                       : edgeLengthMetrics(input);
    require(
        m.size() == input.points.size(), ErrorCode::InvalidArgument,
        "metrics: " + std::to_string(m.size()) + " tensors for " + std::to_string(input.points.size()) + " vertices");
    RemeshOptions o;
    if (options.hasOwnProperty("hmin")) o.hmin = options["hmin"].as<double>();
    if (options.hasOwnProperty("hmax")) o.hmax = options["hmax"].as<double>();
    if (options.hasOwnProperty("hgrad")) o.hgrad = options["hgrad"].as<double>();
    if (options.hasOwnProperty("maxElements"))
      o.mesher.maxElements = static_cast<std::int64_t>(options["maxElements"].as<double>());
    const val onProgress = options["onProgress"];
    if (onProgress.typeOf().as<std::string>() == "function")
      o.mesher.progress = [onProgress](double fraction) { return !onProgress(fraction).isFalse(); };
    // onStage(name) as each stage starts ("boundary", "control space", "discretization",
    // "meshing", as the CLI's -v 1 lines, then "output": the results copied out to JS): lets a
    // caller time the stages. false cancels (the JS layer answers false for a callback that threw).
    const val onStage = options["onStage"];
    if (onStage.typeOf().as<std::string>() == "function")
      o.onStage = [onStage](const char* stage) {
        if (onStage(std::string(stage)).isFalse()) throw Error(ErrorCode::Cancelled, "remesh: cancelled by onStage");
      };
    std::unique_ptr<AdaptiveControlSpace> cs;
    CaseRun run;
    // Moved in, as the CLI does: the input and its metrics are freed once the control space
    // is built (the wasm heap's peak on large carriers).
    run.mesh = remesh(std::move(input), std::move(m), o, &run.report, &cs);
    run.finalSpace = std::move(cs);
    if (o.onStage) o.onStage("output");  // the mesh out to JS (and the report, unless stats: false)
    val r = val::object();
    r.set("mesh", meshToJs(run.mesh));
    if (wantsSvg(options)) r.set("svg", textToJs(caseRunSvg(run, svgOptions(options))));
    if (options["vtu"].isTrue()) r.set("vtu", textToJs(caseRunVtu(run)));
    if (options["stats"].isFalse()) {
      // No report now (the CLI makes none without --stats): the run is kept for report().
      r.set("stats", val::null());
      r.set("report", val(std::make_shared<CaseReportHandle>(std::move(run))));
      return r;
    }
    // The same report as the native CLI's remesh --stats.
    r.set("stats", textToJs(pipelineStatsJson(run.mesh, *run.finalSpace, run.report).dump()));
    return r;
  });
}

// Field-metric and adaptation options from a plain object (api.js has checked the types):
// { err, relative, nv, norm: 1 | 2 | 'inf', shape, hmin, hmax, anisomax, maxElements,
//   iterations, hgrad }.
AdaptOptions adaptOptionsFromJs(const val& js) {
  AdaptOptions o;
  FieldMetricOptions& m = o.metric;
  auto num = [&js](const char* key, double* out) {
    if (js.hasOwnProperty(key)) *out = js[key].as<double>();
  };
  num("err", &m.err);
  num("nv", &m.targetVertices);
  num("hmin", &m.hmin);
  num("hmax", &m.hmax);
  num("anisomax", &m.anisomax);
  num("hgrad", &o.hgrad);
  if (js.hasOwnProperty("relative")) m.relativeError = js["relative"].as<bool>();
  if (js.hasOwnProperty("maxElements")) m.maxElements = static_cast<std::int64_t>(js["maxElements"].as<double>());
  if (js.hasOwnProperty("iterations")) o.iterations = js["iterations"].as<int>();
  if (js.hasOwnProperty("norm")) {
    const std::string n = js["norm"].as<std::string>();
    m.norm = n == "1" ? ErrorNorm::L1 : n == "2" ? ErrorNorm::L2 : ErrorNorm::Linf;
  }
  if (js.hasOwnProperty("shape")) {
    const std::string sh = js["shape"].as<std::string>();
    m.shape = sh == "isotropic" ? MetricShape::Isotropic
              : sh == "uniform" ? MetricShape::Uniform
                                : MetricShape::Anisotropic;
  }
  return o;
}

// Per-vertex values (Float64Array each) from a JS array.
std::vector<std::vector<double>> fieldsFromJs(const val& fields) {
  std::vector<std::vector<double>> out;
  const int n = fields["length"].as<int>();
  for (int i = 0; i < n; ++i) out.push_back(emscripten::convertJSArrayToNumberVector<double>(fields[i]));
  return out;
}

// The metric of fields on mesh: { metrics (m11, m12, m22 per vertex), complexity, expectedVertices, hmin, hmax }.
val metricFromFieldJs(val mesh, val fields, val options) {
  return guarded([&] {
    const Mesh input = meshFromJs(mesh);
    const FieldMetric fm = metricFromFields(input, fieldsFromJs(fields), adaptOptionsFromJs(options).metric);
    std::vector<double> flat;
    flat.reserve(3 * fm.metrics.size());
    for (const Metric& m : fm.metrics) {
      const Mat2 t = m.tensor();
      flat.push_back(t(0, 0));
      flat.push_back(t(0, 1));
      flat.push_back(t(1, 1));
    }
    val r = val::object();
    r.set("metrics", typedCopy(flat.data(), flat.size()));
    r.set("complexity", fm.complexity);
    r.set("expectedVertices", fm.expectedVertices);
    r.set("hmin", fm.hmin);
    r.set("hmax", fm.hmax);
    return r;
  });
}

// The adaptation loop: fields are per-vertex values (transferred) or expressions in x, y
// (re-sampled); { mesh, fields, iterations, measures? }.
val adaptJs(val mesh, val fields, val expressions, val options) {
  return guarded([&] {
    const Mesh input = meshFromJs(mesh);
    const AdaptOptions o = adaptOptionsFromJs(options);
    AdaptResult r;
    const int ne = expressions["length"].as<int>();
    if (ne > 0) {
      std::vector<FieldFunction> fns;
      for (int i = 0; i < ne; ++i) {
        ExpressionOptions eo;
        eo.name = "field";
        eo.uName = "x";
        eo.vName = "y";
        const Expression e = Expression::parse(expressions[i].as<std::string>(), eo);
        fns.push_back([e](const Vec2& p) { return e.value(p.x(), p.y()); });
      }
      r = adaptToFunctions(input, fns, o);
    } else {
      r = adaptToFields(input, fieldsFromJs(fields), o);
    }
    val out = val::object();
    out.set("mesh", meshToJs(r.mesh));
    val fs = val::array();
    for (const auto& f : r.fields) fs.call<void>("push", typedCopy(f.data(), f.size()));
    out.set("fields", fs);
    val its = val::array();
    for (const AdaptIteration& it : r.iterations) {
      val j = val::object();
      j.set("vertices", it.vertices);
      j.set("triangles", it.triangles);
      j.set("complexity", it.complexity);
      j.set("expectedVertices", it.expectedVertices);
      j.set("estimatedError", it.estimatedError);
      if (it.errorLinf >= 0) {
        j.set("errorLinf", it.errorLinf);
        j.set("errorL2", it.errorL2);
      }
      j.set("seconds", it.seconds);
      its.call<void>("push", j);
    }
    out.set("iterations", its);
    // measures: the last mesh measured in the last iteration's control space (as meshCase).
    if (options["measures"].isTrue()) out.set("measures", meshMeasures(r.mesh, r.controlSpace.get()));
    return out;
  });
}

// Checks an expression in two variables (u, v unless renamed, e.g. x, y); returns its
// value at (u, v) or the parse error.
val checkExpression(std::string text, double u, double v, std::string uName, std::string vName) {
  return guarded([&] {
    ExpressionOptions o;
    o.name = "expression";
    o.uName = uName;
    o.vName = vName;
    const Expression e = Expression::parse(text, o);
    val out = val::object();
    out.set("value", e.value(u, v));
    return out;
  });
}

// A long-lived control space built from the "controlSpace", "sources" and "domain"
// parts of a JSON case; JS owns it and frees it with delete() (the wrapper's dispose()).
class ControlSpaceHandle {
 public:
  val build(std::string jsonText) {
    return guarded([&] {
      const CaseSpec spec = parseCaseJson(jsonText);
      cs_ = buildCaseControlSpace(spec);
      val out = val::object();
      out.set("ok", true);
      return out;
    });
  }
  // The initial control space (section 3.1) of patch `patch` of a surface case
  // (buildPatchControlSpace: curvature metric, its sources, contour curvature, 3D sources).
  val buildPatch(std::string jsonText, int patch) {
    return guarded([&] {
      const SurfaceCaseSpec spec = parseSurfaceCaseJson(jsonText);
      const int n = int(spec.model.patches.size());
      require(patch >= 0 && patch < n, ErrorCode::InvalidArgument,
              "patch " + std::to_string(patch) + " out of range (the case has " + std::to_string(n) + " patches)");
      cs_ = std::shared_ptr<const ControlSpace>(
          buildPatchControlSpace(spec.model.patches[size_t(patch)], spec.model.sources3d, spec.options));
      val out = val::object();
      out.set("ok", true);
      out.set("patches", n);
      return out;
    });
  }
  // The exact minimum of two built control spaces (minimumOf: a minimum passes on its
  // inputs); the inputs are shared, so disposing them later leaves this one valid.
  val buildMinimum(const ControlSpaceHandle& a, const ControlSpaceHandle& b) {
    return guarded([&] {
      require(a.cs_ != nullptr && b.cs_ != nullptr, ErrorCode::InvalidArgument,
              "minimum of a control space that is not built");
      cs_ = minimumOf(a.cs_, b.cs_);
      val out = val::object();
      out.set("ok", true);
      return out;
    });
  }
  // Metrics at n points (xy interleaved): Float64Array of m11, m12, m22 per point.
  val metricsAt(val xy) {
    return guarded([&] {
      require(cs_ != nullptr, ErrorCode::InvalidArgument, "control space is not built");
      const auto p = emscripten::convertJSArrayToNumberVector<double>(xy);
      std::vector<double> m(3 * (p.size() / 2));
      for (size_t i = 0; 2 * i + 1 < p.size(); ++i) {
        const Mat2 t = cs_->metricAt(Vec2(p[2 * i], p[2 * i + 1])).tensor();
        m[3 * i] = t(0, 0);
        m[3 * i + 1] = t(0, 1);
        m[3 * i + 2] = t(1, 1);
      }
      val out = val::object();
      out.set("metrics", typedCopy(m.data(), m.size()));
      return out;
    });
  }
  // Nodes and cells for display, as JSON text (see io/control_space_export.h).
  val inspect(int sampleGrid) {
    return guarded([&] {
      require(cs_ != nullptr, ErrorCode::InvalidArgument, "control space is not built");
      val out = val::object();
      if (const auto* a = dynamic_cast<const AdaptiveControlSpace*>(cs_.get()))
        out.set("json", textToJs(controlSpaceToJson(*a).dump()));
      else
        out.set("json", textToJs(sampledControlSpaceToJson(*cs_, sampleGrid, sampleGrid).dump()));
      return out;
    });
  }
  val toVtk() {
    return guarded([&] {
      const auto* a = dynamic_cast<const AdaptiveControlSpace*>(cs_.get());
      require(a != nullptr, ErrorCode::InvalidArgument,
              "only an adaptive control space (quadtree or background mesh) exports to VTK, not a minimum");
      val out = val::object();
      out.set("text", textToJs(controlSpaceToVtk(*a)));
      return out;
    });
  }

 private:
  std::shared_ptr<const ControlSpace> cs_;
};

// A planar domain (JSON text of a case's "domain") from an SVG drawing (io/svg_import.h).
val domainFromSvg(std::string svgText, double size, bool flipY) {
  return guarded([&] {
    SvgImportOptions o;
    o.size = size;
    o.flipY = flipY;
    val out = val::object();
    out.set("json", domainJsonFromSvg(svgText, o).dump());
    return out;
  });
}

std::string coreVersion() { return anisomesh::version(); }

// Sets the threads of the parallel stages (clamped: always 1 in the single-threaded module,
// the caller and the worker pool in the threaded one) and returns the count in effect.
int setThreads(int threads) {
#if defined(__EMSCRIPTEN_PTHREADS__)
  // A thread beyond the pool started with the module would wait for the caller's event loop
  // (wasm/threads_pre.js sizes the pool).
  threads = std::min(threads, EM_ASM_INT({ return Module['anisomeshPoolSize'] | 0; }) + 1);
#endif
  setThreadCount(threads);
  return threadCount();
}

// Bytes of the wasm heap in use by malloc and the heap's total size: lets tests and
// users check that repeated runs leak nothing.
val memoryStats() {
  const struct mallinfo mi = mallinfo();
  val out = val::object();
  out.set("inUseBytes", static_cast<double>(mi.uordblks));
  out.set("heapBytes", static_cast<double>(emscripten::val::module_property("HEAP8")["length"].as<double>()));
  return out;
}

}  // namespace

EMSCRIPTEN_BINDINGS(anisomesh) {
  emscripten::function("version", &coreVersion);
  emscripten::function("metricCreate", &metricCreate);
  emscripten::function("metricIntersect", &metricIntersect);
  emscripten::function("metricInterpolate", &metricInterpolate);
  emscripten::function("metricLength", &metricLength);
  emscripten::function("metricDifference", &metricDifference);
  emscripten::function("metricEllipse", &metricEllipseJs);
  emscripten::function("memoryStats", &memoryStats);
  emscripten::function("setThreads", &setThreads);
  emscripten::function("meshCase", &meshCaseJson);
  emscripten::function("remesh", &remeshJs);
  emscripten::function("metricFromField", &metricFromFieldJs);
  emscripten::function("adapt", &adaptJs);
  emscripten::function("writeMesh", &writeMeshText);
  emscripten::function("readMesh", &readMeshText);
  emscripten::function("readSol", &readSolText);
  emscripten::function("writeSol", &writeSolText);
  emscripten::function("checkExpression", &checkExpression);
  emscripten::function("domainFromSvg", &domainFromSvg);
  emscripten::class_<CaseReportHandle>("CaseReportHandle")
      .smart_ptr<std::shared_ptr<CaseReportHandle>>("CaseReportHandlePtr")
      .function("stats", &CaseReportHandle::stats)
      .function("elementMeasures", &CaseReportHandle::elementMeasures);
  emscripten::class_<ControlSpaceHandle>("ControlSpaceHandle")
      .constructor<>()
      .function("build", &ControlSpaceHandle::build)
      .function("buildMinimum", &ControlSpaceHandle::buildMinimum)
      .function("buildPatch", &ControlSpaceHandle::buildPatch)
      .function("metricsAt", &ControlSpaceHandle::metricsAt)
      .function("inspect", &ControlSpaceHandle::inspect)
      .function("toVtk", &ControlSpaceHandle::toVtk);
}

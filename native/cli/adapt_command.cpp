// anisomesh adapt: the adaptation loop on the command line (names after BAMG and MMG:
// -err, -nv, -hmin, -hmax, -hgrad, -anisomax, -sol).
#include "adapt_command.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "anisomesh/adapt/adaptation_loop.h"
#include "anisomesh/core/error.h"
#include "anisomesh/geometry/expression.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/mesh_formats.h"
#include "anisomesh/io/svg.h"

namespace anisomesh {
namespace {

const char* kAdaptUsage =
    "usage: anisomesh adapt IN.mesh (-sol FIELD.sol | -field 'EXPR in x, y')... -o OUT.mesh\n"
    "         (-err E [-relative] | -nv N) [-norm 1|2|inf] [-hmin H] [-hmax H] [-anisomax R] [-hgrad R]\n"
    "         [-iterations K] [-isotropic | -uniform] [-svg PIC.svg] [--max-elements N] [--stats]\n"
    "         [--control-threshold T]\n"
    "  adapts IN.mesh K times (default 3) to the fields: Hessian recovery, metric of error level E\n"
    "  (absolute, or relative to the field's range) or of N vertices minimizing the L^p interpolation\n"
    "  error (-norm, default inf), remeshing, field transfer (-sol) or re-sampling (-field).\n"
    "  IN and OUT: .mesh, .meshb, .msh, .vtk, .obj (OUT also .svg); the fields are written at OUT's\n"
    "  vertices beside it (OUT's stem + .sol, .solb for a .meshb OUT; several fields: stem.1.sol,\n"
    "  stem.2.sol, ...); -sol reads .sol or .solb; -svg: a picture coloured by the first field.\n"
    "  --control-threshold: metric difference splitting a control-space element (default 1).\n"
    "  Prints one line per iteration (--stats: one JSON object instead).\n";

struct AdaptUsageError {
  std::string message;
};

double number(const std::string& option, const char* text, double lo) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v >= lo) || v > 1e300)
    throw AdaptUsageError{option + " expects a number >= " + std::to_string(lo) + ", got '" + text + "'"};
  return v;
}

std::string stem(const std::string& path) {
  const std::string ext = fileExtension(path);
  return ext.empty() ? path : path.substr(0, path.size() - ext.size() - 1);
}

// Picture of the mesh, elements coloured by the mean of the field at their vertices.
std::string fieldSvg(const Mesh& mesh, const std::vector<double>& field) {
  SvgOptions o;
  o.width = 900;
  o.strokeWidth = 0.25;
  const auto mm = std::minmax_element(field.begin(), field.end());
  const double lo = *mm.first, span = *mm.second - *mm.first;
  auto value = [&](const int* v, int k) {
    double s = 0;
    for (int i = 0; i < k; ++i) s += field[size_t(v[i])];
    return span > 0 ? (s / k - lo) / span : 0.5;
  };
  for (const auto& t : mesh.triangles) o.elementValues.push_back(value(t.data(), 3));
  for (const auto& q : mesh.quads) o.elementValues.push_back(value(q.data(), 4));
  return writeSvg(mesh, o);
}

int run(int argc, char** argv) {
  std::string input, output, svg;
  std::vector<std::string> sols, exprs;
  AdaptOptions o;
  bool stats = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw AdaptUsageError{a + " expects a value"};
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << kAdaptUsage;
      return 0;
    }
    if (a == "-o" || a == "--output")
      output = value();
    else if (a == "-sol" || a == "--sol")
      sols.push_back(value());
    else if (a == "-field" || a == "--field")
      exprs.push_back(value());
    else if (a == "-err")
      o.metric.err = number(a, value(), 1e-300);
    else if (a == "-relative")
      o.metric.relativeError = true;
    else if (a == "-nv")
      o.metric.targetVertices = number(a, value(), 1);
    else if (a == "-norm") {
      const std::string v = value();
      if (v == "1")
        o.metric.norm = ErrorNorm::L1;
      else if (v == "2")
        o.metric.norm = ErrorNorm::L2;
      else if (v == "inf" || v == "0")
        o.metric.norm = ErrorNorm::Linf;
      else
        throw AdaptUsageError{"-norm expects 1, 2 or inf, got '" + v + "'"};
    } else if (a == "-hmin")
      o.metric.hmin = number(a, value(), 0);
    else if (a == "-hmax")
      o.metric.hmax = number(a, value(), 0);
    else if (a == "-anisomax")
      o.metric.anisomax = number(a, value(), 1);
    else if (a == "-hgrad")
      o.hgrad = number(a, value(), 0);
    else if (a == "-iterations") {
      const double k = number(a, value(), 1);
      if (k != std::floor(k) || k > kMaxAdaptIterations)
        throw AdaptUsageError{"-iterations expects an integer in [1, " + std::to_string(kMaxAdaptIterations) + "]"};
      o.iterations = int(k);
    } else if (a == "-isotropic")
      o.metric.shape = MetricShape::Isotropic;
    else if (a == "-uniform")
      o.metric.shape = MetricShape::Uniform;
    else if (a == "--control-threshold")
      o.refineThreshold = number(a, value(), 1e-3);
    else if (a == "-svg")
      svg = value();
    else if (a == "--max-elements") {
      const double k = number(a, value(), 1);
      o.metric.maxElements = static_cast<std::int64_t>(k);
    } else if (a == "--stats")
      stats = true;
    else if (!a.empty() && a[0] == '-')
      throw AdaptUsageError{"unknown option '" + a + "' for adapt"};
    else if (input.empty())
      input = a;
    else
      throw AdaptUsageError{"unexpected argument '" + a + "'"};
  }
  if (input.empty()) throw AdaptUsageError{"missing IN.mesh"};
  if (output.empty()) throw AdaptUsageError{"missing -o OUT"};
  if (sols.empty() == exprs.empty()) throw AdaptUsageError{"give the fields by -sol or by -field (one of them)"};
  if ((o.metric.err > 0) == (o.metric.targetVertices > 0)) throw AdaptUsageError{"give one of -err E or -nv N"};
  if (o.hgrad > 0 && o.hgrad < 1) throw AdaptUsageError{"-hgrad expects a ratio >= 1 (or 0: off)"};
  if (fileExtension(output) != "svg") {
    try {
      meshFormatFromPath(output);
    } catch (const Error& e) {
      throw AdaptUsageError{std::string(e.what()) + " (or .svg)"};
    }
  }

  const Mesh mesh = readMeshFile(input);
  AdaptResult r;
  if (!sols.empty()) {
    std::vector<std::vector<double>> fields;
    for (const std::string& s : sols) {
      const SolData sol = readSolFile(s);
      require(sol.type == 1, ErrorCode::ParseError, s + ": adapt needs scalar solutions (type 1)");
      std::string msg = s;
      msg += ": " + std::to_string(sol.count()) + " values for " + std::to_string(mesh.vertexCount());
      msg += " vertices of " + input;
      require(sol.count() == mesh.vertexCount(), ErrorCode::InvalidArgument, msg);
      fields.push_back(sol.values);
    }
    r = adaptToFields(mesh, fields, o);
  } else {
    std::vector<FieldFunction> fns;
    for (size_t k = 0; k < exprs.size(); ++k) {
      ExpressionOptions eo;
      eo.name = "field";
      eo.uName = "x";
      eo.vName = "y";
      const Expression e = Expression::parse(exprs[k], eo);
      fns.push_back([e](const Vec2& p) { return e.value(p.x(), p.y()); });
    }
    r = adaptToFunctions(mesh, fns, o);
  }

  if (fileExtension(output) == "svg")
    writeTextFileAtomic(output, fieldSvg(r.mesh, r.fields[0]));
  else
    writeMeshFile(output, r.mesh);
  for (size_t k = 0; k < r.fields.size(); ++k) {
    SolData sol;
    sol.values = r.fields[k];
    writeSolFile(stem(output) + (r.fields.size() == 1 ? "" : "." + std::to_string(k + 1)) +
                     (fileExtension(output) == "meshb" ? ".solb" : ".sol"),
                 sol);
  }
  if (!svg.empty()) writeTextFileAtomic(svg, fieldSvg(r.mesh, r.fields[0]));

  nlohmann::json its = nlohmann::json::array();
  for (size_t k = 0; k < r.iterations.size(); ++k) {
    const AdaptIteration& it = r.iterations[k];
    nlohmann::json j = {{"iteration", k + 1},
                        {"vertices", it.vertices},
                        {"triangles", it.triangles},
                        {"complexity", it.complexity},
                        {"expectedVertices", it.expectedVertices},
                        {"estimatedError", it.estimatedError},
                        {"seconds", it.seconds},
                        {"secondsMetric", it.secondsMetric},
                        {"secondsControlSpace", it.remesh.secondsControlSpace},
                        {"secondsDiscretization", it.remesh.secondsDiscretization},
                        {"secondsMeshing", it.remesh.secondsMeshing},
                        {"controlElements", it.remesh.controlElements}};
    if (it.errorLinf >= 0) j["errorLinf"] = it.errorLinf, j["errorL2"] = it.errorL2;
    its.push_back(j);
    if (!stats) {
      std::cout << "iteration " << k + 1 << ": " << it.vertices << " vertices, " << it.triangles
                << " triangles, estimated error " << it.estimatedError;
      if (it.errorLinf >= 0) std::cout << ", L-inf error " << it.errorLinf << ", L2 error " << it.errorL2;
      std::cout << " (" << it.seconds << " s)\n";
    }
  }
  if (stats) std::cout << nlohmann::json{{"iterations", its}}.dump() << "\n";
  return 0;
}

}  // namespace

int runAdaptCommand(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const AdaptUsageError& e) {
    std::cerr << "anisomesh: usage error: " << e.message << "\n" << kAdaptUsage;
    return 2;
  }
}

}  // namespace anisomesh

<<<<<<< HEAD
// anisomesh command-line interface (native).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
=======
// anisomesh command-line interface (native). Each command lives in its own file and is
// listed in commands() below; this file dispatches and reports errors.
>>>>>>> main
#include <iostream>
#include <string>
#include <vector>

#include "adapt_command.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/version.h"
#include "cli.h"

namespace {

using namespace anisomesh::cli;

// The command table: add a command by adding its file and one line here.
const std::vector<Command>& commands() {
  static const std::vector<Command> table = {meshCommand(), remeshCommand(), metricCommand()};
  return table;
}

int usage(std::ostream& os, int code) {
<<<<<<< HEAD
  os << "usage: anisomesh <command> [options]\n"
        "commands:\n"
        "  mesh CASE.json -o OUT [--quads] [--all-quads] [--stats] [--max-elements N] [--no-updates]\n"
        "      [--max-control-nodes N] [--max-input-bytes N]\n"
        "                            mesh a JSON case, planar or surface (OUT: .mesh, .vtk, .obj or .svg)\n"
        "      [--svg-uv] [--svg-view AZ,EL] [--svg-control-space]\n"
        "                            .svg of a surface: 3D view from azimuth AZ, elevation EL (degrees;\n"
        "                            default -63,34), or the parameter plane; control-space ellipses over it\n"
        "  remesh IN.mesh -sol IN.sol -o OUT [-hgrad R] [-hmin H] [-hmax H] [--stats] [--max-elements N]\n"
        "      [--max-control-nodes N] [--max-input-bytes N]\n"
        "                            remesh the domain of IN.mesh under the metric IN.sol, used as\n"
        "                            a background-mesh control space (-hgrad: gradation ratio dr >= 1)\n"
        "  metric ALPHA H1 H2        print the metric tensor for sizes (h1, h2) at angle ALPHA (radians)\n"
=======
  os << "usage: anisomesh <command> [options]\ncommands:\n";
  for (const Command& c : commands()) os << c.usage;
  os << "  adapt IN.mesh -sol F.sol|-field EXPR -o OUT (-err E|-nv N) ...\n"
        "                            adapt IN.mesh to a solution (anisomesh adapt --help for the options)\n"
>>>>>>> main
        "  --version                 print the version\n"
        "--max-control-nodes: control-space node budget (default: max-elements / 64 + 262144);\n"
        "--max-input-bytes: larger input files are refused (default 536870912).\n"
        "--stats prints one JSON object on stdout. Errors: exit 1 (bad input), 2 (bad usage).\n";
  return code;
}

<<<<<<< HEAD
// A command-line mistake: reported with the usage text, exit code 2.
struct UsageError {
  std::string message;
};

double parseNumber(const std::string& option, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v >= 0) || v > 1e300)
    throw UsageError{option + " expects a nonnegative number, got '" + text + "'"};
  return v;
}

long long parseCount(const std::string& option, const char* text) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || v <= 0 || errno == ERANGE)
    throw UsageError{option + " expects a positive integer, got '" + text + "'"};
  return v;
}

// A finite number (any sign) for the positional argument named name.
double parseReal(const std::string& name, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v))
    throw UsageError{name + " expects a finite number, got '" + text + "'"};
  return v;
}

// Walks argv after the command: positionals, flags and options with a value.
class Args {
 public:
  Args(int argc, char** argv) : argc_(argc), argv_(argv) {}
  bool done() const { return i_ >= argc_; }
  std::string next() { return argv_[i_++]; }
  const char* value(const std::string& option) {
    if (i_ >= argc_) throw UsageError{option + " expects a value"};
    return argv_[i_++];
  }

 private:
  int argc_;
  char** argv_;
  int i_ = 2;
};

bool isSvg(const std::string& path) { return fileExtension(path) == "svg"; }

void requireOutput(const std::string& out) {
  if (out.empty()) throw UsageError{"missing -o OUT"};
  if (isSvg(out)) return;
  try {
    meshFormatFromPath(out);
  } catch (const Error& e) {
    throw UsageError{std::string(e.what()) + " (or .svg)"};
  }
}

// How .svg pictures are drawn (mesh command options).
struct SvgChoice {
  bool uv = false;                         // --svg-uv: surface meshes in the parameter plane
  bool controlSpace = false;               // --svg-control-space: surface control spaces drawn over the mesh
  double azimuth = -1.1, elevation = 0.6;  // --svg-view AZ,EL (degrees in, radians here)
};

// Writes the mesh by extension; .svg pictures colour elements by metric quality (planar:
// in the final control space; surface: in 3D), surfaces in a 3D view unless choice.uv.
void writeOutput(const std::string& path, const CaseRun& run, const SvgChoice& choice) {
  const Mesh& mesh = run.mesh;
  if (!isSvg(path)) return writeMeshFile(path, mesh);
  SvgOptions o;
  o.width = 900;
  o.strokeWidth = 0.3;
  if (run.finalSpace)
    o.elementValues = elementQualities(mesh, *run.finalSpace);
  else if (run.elementQuality.size() == size_t(mesh.elementCount()) && run.glyphs.empty())
    o.elementValues = run.elementQuality;  // (plain elements under control-space glyphs)
  o.view3d = mesh.dimension == 3 && !choice.uv;
  o.azimuth = choice.azimuth;
  o.elevation = choice.elevation;
  for (const auto& g : run.glyphs) {
    o.overlay.emplace_back();
    if (o.view3d)
      o.overlay.back() = g.xyz;
    else
      for (const Vec2& p : g.uv) o.overlay.back().emplace_back(p.x(), p.y(), 0.0);
  }
  writeTextFileAtomic(path, writeSvg(mesh, o));
}

int runMesh(int argc, char** argv) {
  Args args(argc, argv);
  std::string input, output;
  bool stats = false, quads = false, allQuads = false, updates = true;
  long long maxElements = -1, maxControlNodes = -1;
  SvgChoice svg;
  while (!args.done()) {
    const std::string a = args.next();
    if (a == "-o" || a == "--output")
      output = args.value(a);
    else if (a == "--svg-uv")
      svg.uv = true;
    else if (a == "--svg-control-space")
      svg.controlSpace = true;
    else if (a == "--svg-view") {
      const std::string v = args.value(a);
      char* end = nullptr;
      const double az = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != ',')
        throw UsageError{a + " expects AZIMUTH,ELEVATION in degrees, got '" + v + "'"};
      const char* rest = end + 1;
      const double el = std::strtod(rest, &end);
      if (end == rest || *end != '\0' || !std::isfinite(az) || !std::isfinite(el))
        throw UsageError{a + " expects AZIMUTH,ELEVATION in degrees, got '" + v + "'"};
      svg.azimuth = az * 0.017453292519943295;
      svg.elevation = el * 0.017453292519943295;
    } else if (a == "--quads")
      quads = true;
    else if (a == "--all-quads")
      allQuads = true;
    else if (a == "--stats")
      stats = true;
    else if (a == "--no-updates")
      updates = false;
    else if (a == "--max-elements")
      maxElements = parseCount(a, args.value(a));
    else if (a == "--max-control-nodes")
      maxControlNodes = parseCount(a, args.value(a));
    else if (a == "--max-input-bytes")
      setDefaultMaxInputBytes(parseCount(a, args.value(a)));
    else if (!a.empty() && a[0] == '-')
      throw UsageError{"unknown option '" + a + "' for mesh"};
    else if (input.empty())
      input = a;
    else
      throw UsageError{"unexpected argument '" + a + "'"};
  }
  if (input.empty()) throw UsageError{"missing CASE.json"};
  requireOutput(output);

  // The same entry point as the wasm package: planar and surface cases, same report.
  RunCaseOptions o;
  if (quads) o.quads = true;
  if (allQuads) o.allQuads = true;
  o.maxElements = maxElements;
  o.maxControlNodes = maxControlNodes;
  o.controlSpaceUpdates = updates;
  o.controlSpaceGlyphs = svg.controlSpace && isSvg(output);
  const CaseRun run = runCase(withStage("reading the case file", [&] { return readTextFile(input); }), o);
  withStage("writing the output", [&] { writeOutput(output, run, svg); });
  if (stats) std::cout << run.stats.dump() << "\n";
  return 0;
}

int runRemesh(int argc, char** argv) {
  Args args(argc, argv);
  std::string input, sol, output;
  bool stats = false;
  RemeshOptions options;
  while (!args.done()) {
    const std::string a = args.next();
    if (a == "-o" || a == "--output")
      output = args.value(a);
    else if (a == "-sol" || a == "--sol")
      sol = args.value(a);
    else if (a == "-hgrad" || a == "--hgrad")
      options.hgrad = parseNumber(a, args.value(a));
    else if (a == "-hmin" || a == "--hmin")
      options.hmin = parseNumber(a, args.value(a));
    else if (a == "-hmax" || a == "--hmax")
      options.hmax = parseNumber(a, args.value(a));
    else if (a == "--stats")
      stats = true;
    else if (a == "--max-elements")
      options.mesher.maxElements = parseCount(a, args.value(a));
    else if (a == "--max-control-nodes")
      options.maxControlNodes = parseCount(a, args.value(a));
    else if (a == "--max-input-bytes")
      setDefaultMaxInputBytes(parseCount(a, args.value(a)));
    else if (!a.empty() && a[0] == '-')
      throw UsageError{"unknown option '" + a + "' for remesh"};
    else if (input.empty())
      input = a;
    else
      throw UsageError{"unexpected argument '" + a + "'"};
  }
  if (input.empty()) throw UsageError{"missing IN.mesh"};
  if (sol.empty()) throw UsageError{"missing -sol IN.sol"};
  requireOutput(output);
  if (options.hmin > 0 && options.hmax > 0 && options.hmin > options.hmax)
    throw UsageError{"-hmin must not exceed -hmax"};
  if (options.hgrad > 0 && options.hgrad < 1) throw UsageError{"-hgrad expects a ratio >= 1 (or 0: off)"};

  const Mesh in = withStage("reading IN.mesh", [&] { return readMeditFile(input); });
  const std::vector<Metric> metrics =
      withStage("reading IN.sol", [&] { return solToMetrics(readSolFile(sol), in.vertexCount()); });
  PipelineReport report;
  std::unique_ptr<AdaptiveControlSpace> cs;
  CaseRun run;
  run.mesh = remesh(in, metrics, options, &report, &cs);
  run.finalSpace = std::move(cs);
  withStage("writing the output", [&] { writeOutput(output, run, SvgChoice{}); });
  if (stats) std::cout << pipelineStatsJson(run.mesh, *run.finalSpace, report).dump() << "\n";
  return 0;
}

=======
>>>>>>> main
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage(std::cerr, 2);
  const std::string cmd = argv[1];
  try {
    if (cmd == "--version") {
      std::cout << "anisomesh " << anisomesh::version() << "\n";
      return 0;
    }
    if (cmd == "--help" || cmd == "-h") return usage(std::cout, 0);
<<<<<<< HEAD
    if (cmd == "metric") {
      if (argc != 5) return usage(std::cerr, 2);
      const auto m = anisomesh::Metric::fromSizes(parseReal("metric ALPHA", argv[2]), parseReal("metric H1", argv[3]),
                                                  parseReal("metric H2", argv[4]));
      const auto t = m.tensor();
      std::cout << "{\"m11\":" << t(0, 0) << ",\"m12\":" << t(0, 1) << ",\"m22\":" << t(1, 1) << "}\n";
      return 0;
=======
    for (const Command& c : commands()) {
      if (c.name != cmd) continue;
      Args args(argc, argv);
      return c.run(args);
>>>>>>> main
    }
    if (cmd == "adapt") return anisomesh::runAdaptCommand(argc, argv);
    std::cerr << "anisomesh: unknown command '" << cmd << "'\n";
    return usage(std::cerr, 2);
  } catch (const UsageError& e) {
    std::cerr << "anisomesh: usage error: " << e.message << "\n";
    return usage(std::cerr, 2);
  } catch (const anisomesh::Error& e) {
    std::cerr << "anisomesh: error " << anisomesh::errorCodeName(e.code()) << ": " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "anisomesh: error OUT_OF_MEMORY: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "anisomesh: error INTERNAL: " << e.what() << "\n";
    return 1;
  }
}

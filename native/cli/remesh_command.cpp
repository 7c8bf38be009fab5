// anisomesh remesh IN.mesh [-sol IN.sol] -o OUT ...: remeshes a mesh's domain under a
// metric (MMG's flags where MMG has them).
#include <iostream>
#include <memory>

#include "anisomesh/io/file_io.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/mesh_formats.h"
#include "anisomesh/pipeline/input_size_metrics.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "anisomesh/pipeline/pipeline.h"
#include "cli.h"

namespace anisomesh::cli {

namespace {

int runRemesh(Args& args) {
  std::string input, sol, output;
  bool stats = false;
  double hsiz = 0;
  int verbosity = 0;
  RemeshOptions options;
  while (!args.done()) {
    const std::string a = args.next();
    if (a == "-o" || a == "--output" || a == "-out")
      output = args.value(a);
    else if (a == "-in")
      input = args.value(a);
    else if (a == "-sol" || a == "--sol")
      sol = args.value(a);
    else if (a == "-hgrad" || a == "--hgrad") {
      const double r = parseSignedNumber(a, args.value(a));
      if (r == -1) {
        options.hgrad = 0;  // MMG: -hgrad -1 turns gradation off
      } else {
        if (r < 0 || (r > 0 && r < 1)) throw UsageError{a + " expects a ratio >= 1, 0 or -1 (off)"};
        options.hgrad = r;
      }
    } else if (a == "-hmin" || a == "--hmin")
      options.hmin = parseNumber(a, args.value(a));
    else if (a == "-hmax" || a == "--hmax")
      options.hmax = parseNumber(a, args.value(a));
    else if (a == "-hsiz" || a == "--hsiz") {
      hsiz = parseNumber(a, args.value(a));
      if (!(hsiz > 0)) throw UsageError{a + " expects a positive size"};
    } else if (a == "-v")
      verbosity = static_cast<int>(parseSignedNumber(a, args.value(a)));
    else if (a == "--stats")
      stats = true;
    else if (a == "--max-control-nodes")
      options.maxControlNodes = parseCount(a, args.value(a));
    else if (a == "--max-input-bytes")
      setDefaultMaxInputBytes(parseCount(a, args.value(a)));
    else if (a == "--max-elements")
      options.mesher.maxElements = parseCount(a, args.value(a));
    else if (!a.empty() && a[0] == '-')
      throw UsageError{"unknown option '" + a + "' for remesh"};
    else if (input.empty())
      input = a;
    else
      throw UsageError{"unexpected argument '" + a + "'"};
  }
  if (input.empty()) throw UsageError{"missing IN.mesh"};
  if (sol.empty() && hsiz == 0 && options.hmin == 0 && options.hmax == 0)
    throw UsageError{"missing -sol IN.sol (or -hsiz H, -hmin H, -hmax H for isotropic sizes)"};
  if (!sol.empty() && hsiz > 0) throw UsageError{"-hsiz and -sol exclude each other"};
  requireOutput(output);
  if (options.hmin > 0 && options.hmax > 0 && options.hmin > options.hmax)
    throw UsageError{"-hmin must not exceed -hmax"};
  options.mesher.progress = progressPrinter(verbosity);

  const Mesh in = readMeshFile(input);  // .mesh, .msh, .vtk or .obj by extension
  const std::vector<Metric> metrics = !sol.empty() ? solToMetrics(readSolFile(sol), in.vertexCount())
                                      : hsiz > 0   ? uniformMetrics(in, hsiz)
                                                   : edgeLengthMetrics(in);
  PipelineReport report;
  std::unique_ptr<AdaptiveControlSpace> cs;
  CaseRun run;
  run.mesh = remesh(in, metrics, options, &report, &cs);
  run.finalSpace = std::move(cs);
  writeOutput(output, run, CaseSvgOptions{});
  if (stats) std::cout << pipelineStatsJson(run.mesh, *run.finalSpace, report).dump() << "\n";
  return 0;
}

}  // namespace

Command remeshCommand() {
  return {"remesh",
          "  remesh IN.mesh [-sol IN.sol] -o OUT [-hgrad R] [-hmin H] [-hmax H] [-hsiz H] [-v N] [--stats]\n"
          "         [--max-elements N]\n"
          "                            remesh the domain of IN.mesh (or .msh, .vtk, .obj) under the metric IN.sol, as\n"
          "                            a background-mesh control space (-hgrad: gradation ratio dr >= 1,\n"
          "                            -1 or 0: off); without -sol: isotropic sizes, -hsiz H everywhere or\n"
          "                            the input's edge lengths clamped to [-hmin, -hmax]; -in / -out as in MMG\n",
          runRemesh};
}

}  // namespace anisomesh::cli

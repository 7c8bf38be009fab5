// anisomesh mesh CASE.json -o OUT ...: meshes a JSON case, planar or surface.
#include <algorithm>
#include <iostream>

#include "anisomesh/core/parallel.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/run_case.h"
#include "cli.h"

namespace anisomesh::cli {

namespace {

int runMesh(Args& args) {
  std::string input, output;
  bool stats = false, quads = false, allQuads = false, updates = true, glyphs = false;
  std::int64_t maxElements = -1, maxControlNodes = -1;
  int verbosity = 0;
  long long threads = 1;
  CaseSvgOptions svg;
  while (!args.done()) {
    const std::string a = args.next();
    if (a == "-o" || a == "--output" || a == "-out")
      output = args.value(a);
    else if (a == "-in")
      input = args.value(a);
    else if (a == "-v")
      verbosity = static_cast<int>(parseSignedNumber(a, args.value(a)));
    else if (a == "--svg-uv")
      svg.uv = true;
    else if (a == "--svg-control-space")
      glyphs = true;
    else if (a == "--svg-view")
      parseView(a, args.value(a), svg);
    else if (a == "--quads")
      quads = true;
    else if (a == "--all-quads")
      allQuads = true;
    else if (a == "--stats")
      stats = true;
    else if (a == "--no-updates")
      updates = false;
    else if (a == "-threads" || a == "--threads")
      threads = parseCount(a, args.value(a));
    else if (parseBudgetOption(a, args, &maxElements, &maxControlNodes))
      continue;
    else if (!a.empty() && a[0] == '-')
      throw UsageError{"unknown option '" + a + "' for mesh"};
    else if (input.empty())
      input = a;
    else
      throw UsageError{"unexpected argument '" + a + "'"};
  }
  if (input.empty()) throw UsageError{"missing CASE.json"};
  requireOutput(output);
  setThreadCount(int(std::min<long long>(threads, 256)));

  // The same entry point as the wasm package: planar and surface cases, same report.
  RunCaseOptions o;
  if (quads) o.quads = true;
  if (allQuads) o.allQuads = true;
  o.maxElements = maxElements;
  o.maxControlNodes = maxControlNodes;
  o.controlSpaceUpdates = updates;
  o.controlSpaceGlyphs = glyphs && isSvg(output);
  o.progress = progressPrinter(verbosity);
  const CaseRun run = runCase(readTextFile(input), o);
  writeOutput(output, run, svg);
  if (stats) std::cout << run.stats.dump() << "\n";
  return 0;
}

}  // namespace

Command meshCommand() {
  return {
      "mesh",
      "  mesh CASE.json -o OUT [--quads] [--all-quads] [--stats] [--max-elements N] [--no-updates] [-v N]\n"
      "       [-threads N]\n"
      "                            mesh a JSON case, planar or surface (OUT: .mesh, .vtk, .obj, .msh, .vtu or .svg;\n"
      "                            -in CASE.json / -out OUT as in MMG; -v 1: progress on stderr;\n"
      "                            -threads N: worker threads, the same output for any N)\n"
      "      [--svg-uv] [--svg-view AZ,EL] [--svg-control-space]\n"
      "                            .svg of a surface: 3D view from azimuth AZ, elevation EL (degrees;\n"
      "                            default -63,34), or the parameter plane; control-space ellipses over it\n",
      runMesh};
}

}  // namespace anisomesh::cli

// anisomesh remesh IN.mesh [-sol IN.sol] -o OUT ...: remeshes a mesh's domain under a
// metric (MMG's flags where MMG has them).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <iostream>
#include <memory>
#include <utility>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/mesh_formats.h"
#include "anisomesh/io/report_json.h"
#include "anisomesh/pipeline/input_size_metrics.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "anisomesh/pipeline/pipeline.h"
#include "cli.h"

namespace anisomesh::cli {

namespace {

// A "Vm..." line of /proc/self/status in MiB (its unit is kB whatever the page size; the wasm
// CLI under Node reads the host's file, where statm's pages are 4 KiB and not wasm's 64 KiB).
double procStatusMiB(const char* key) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return -1.0;
  char line[256];
  double kib = -1.0;
  const std::size_t n = std::strlen(key);
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, key, n) == 0 && line[n] == ':') {
      kib = std::strtod(line + n + 1, nullptr);
      break;
    }
  std::fclose(f);
  return kib < 0 ? -1.0 : kib / 1024.0;
}

// CPU seconds of the process. Natively clock(); Emscripten's clock() is wall time, so the wasm
// CLI reads the host's /proc/self/stat (utime + stime in USER_HZ = 100 ticks: 10 ms steps).
double processCpuSeconds() {
#if defined(__EMSCRIPTEN__)
  if (std::FILE* f = std::fopen("/proc/self/stat", "r")) {
    char buf[1024];
    const std::size_t len = std::fread(buf, 1, sizeof buf - 1, f);
    std::fclose(f);
    buf[len] = 0;
    const char* p = std::strrchr(buf, ')');  // the command name may hold spaces
    unsigned long long utime = 0, stime = 0;
    if (p && std::sscanf(p + 1, " %*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &utime, &stime) == 2)
      return double(utime + stime) / 100.0;
  }
#endif
  return double(std::clock()) / CLOCKS_PER_SEC;
}

// -v 1 and more: one stderr line per finished stage (wall and process CPU seconds), then
// the peak RSS.
class StageLog {
 public:
  explicit StageLog(bool on) : on_(on) {}
  // Ends the running stage (if any) and starts `name`.
  void start(const char* name) {
    if (!on_) return;
    finish();
    name_ = name;
    wall0_ = std::chrono::steady_clock::now();
    cpu0_ = processCpuSeconds();
  }
  void finish() {
    if (!on_ || name_.empty()) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
    const double cpu = processCpuSeconds() - cpu0_;
    std::fprintf(stderr, "anisomesh: stage %-14s wall %.3f s cpu %.3f s rss %.1f MiB peak %.1f MiB\n", name_.c_str(),
                 wall, cpu, currentRssMiB(), peakRssMiB());
    name_.clear();
  }
  void end() {
    if (!on_) return;
    finish();
    std::fprintf(stderr, "anisomesh: peak RSS %.1f MiB\n", peakRssMiB());
  }
  // The peak resident set (VmHWM; getrusage where /proc is missing).
  static double peakRssMiB() {
    const double hwm = procStatusMiB("VmHWM");
    if (hwm >= 0) return hwm;
    struct rusage ru {};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_maxrss) / 1024.0;
  }
  // The resident set now (VmRSS; 0 where /proc is missing).
  static double currentRssMiB() { return std::max(0.0, procStatusMiB("VmRSS")); }

 private:
  bool on_;
  std::string name_;
  std::chrono::steady_clock::time_point wall0_;
  double cpu0_ = 0;
};

int runRemesh(Args& args) {
  std::string input, sol, output;
  bool stats = false, ridgeAngle = false, noRidges = false;
  double hsiz = 0;
  int verbosity = 0;
  long long threads = 1;
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
    } else if (a == "-hausd" || a == "--hausd") {
      options.hausdorff = parseNumber(a, args.value(a));
      if (!(options.hausdorff > 0)) throw UsageError{a + " expects a positive distance"};
    } else if (a == "-ar" || a == "--ar") {
      const double deg = parseNumber(a, args.value(a));
      if (deg > 180) throw UsageError{a + " expects an angle in degrees from 0 to 180"};
      if (noRidges) throw UsageError{"-ar and -nr exclude each other"};
      ridgeAngle = true;
      options.ridgeAngle = deg * 0.017453292519943295;
    } else if (a == "-nr" || a == "--nr") {
      if (ridgeAngle) throw UsageError{"-ar and -nr exclude each other"};
      noRidges = true;
      options.ridgeAngle = 3.141592653589793;  // no turn is larger: no angle corners
    } else if (a == "-v")
      verbosity = static_cast<int>(parseSignedNumber(a, args.value(a)));
    else if (a == "--stats")
      stats = true;
    else if (a == "-threads" || a == "--threads")
      threads = parseCount(a, args.value(a));
    else if (parseBudgetOption(a, args, &options.mesher.maxElements, &options.maxControlNodes))
      continue;
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

  setThreadCount(int(std::min<long long>(threads, 256)));
  StageLog log(verbosity >= 1);
  if (verbosity >= 1)
    std::fprintf(stderr, "anisomesh: %d threads, transparent huge pages %s\n", threadCount(), hugePagesState());
  log.start("read");
  Mesh in;  // .mesh, .msh, .vtk or .obj by extension; the .sol read beside it
  SolData solData;
  std::vector<Metric> metrics;
  std::exception_ptr metricsError;
  // The two files read concurrently (each parsed in parallel chunks as well): the serial
  // parts of one (sections' headers, the allocations' page faults) overlap the other's
  // parsing. A mapped text is released batch by batch as it is parsed; the mesh's error,
  // if both fail, is the one reported.
  parallelInvoke(
      [&] {
        in = readMeshFile(input);
        // remesh reads the input's points, elements, edges and edge references only.
        std::vector<int>().swap(in.pointRefs);
        std::vector<int>().swap(in.triangleRefs);
        std::vector<int>().swap(in.quadRefs);
      },
      [&] {
        if (sol.empty()) return;
        solData = readSolFile(sol);
        // Converted here too, for the solution's own vertex count: when it is the mesh's,
        // the metrics (or the first error) are those of solToMetrics(solData, mesh count).
        try {
          metrics = solToMetrics(solData, solData.count());
        } catch (const Error&) {
          metricsError = std::current_exception();
        }
      });
  if (!sol.empty()) {
    // A count mismatch is reported first (solToMetrics checks it before the values).
    if (solData.count() != in.vertexCount()) solToMetrics(solData, in.vertexCount());
    if (metricsError) std::rethrow_exception(metricsError);
  } else {
    metrics = hsiz > 0 ? uniformMetrics(in, hsiz) : edgeLengthMetrics(in);
  }
  std::vector<double>().swap(solData.values);  // the metrics hold them now
  PipelineReport report;
  std::unique_ptr<AdaptiveControlSpace> cs;
  CaseRun run;
  options.onStage = [&log](const char* stage) { log.start(stage); };
  // Moved in: the input and its metrics are freed once the control space is built.
  run.mesh = remesh(std::move(in), std::move(metrics), options, &report, &cs);
  run.finalSpace = std::move(cs);
  log.start("write");
  writeOutput(output, run, CaseSvgOptions{});
  if (stats) {
    log.start("report");
    std::cout << pipelineStatsJson(run.mesh, *run.finalSpace, report).dump() << "\n";
  }
  log.finish();
  if (verbosity >= 1) {
    const MesherTimings& mt = report.mesherTimings;
    if (mt.parts > 1) {
      std::fprintf(stderr,
                   "anisomesh: %d triangles; mesher insertion %.3f s, improvement %.3f s (wall, summed over %d "
                   "parts of the domain decomposition)\n",
                   int(run.mesh.triangles.size()), mt.insertion, mt.improvement, mt.parts);
    } else {
      std::fprintf(stderr, "anisomesh: %d triangles; mesher insertion %.3f s, improvement %.3f s (wall)\n",
                   int(run.mesh.triangles.size()), mt.insertion, mt.improvement);
    }
  }
  log.end();
  return 0;
}

}  // namespace

Command remeshCommand() {
  return {"remesh",
          "  remesh IN.mesh [-sol IN.sol] -o OUT [-hgrad R] [-hmin H] [-hmax H] [-hsiz H] [-hausd H]\n"
          "         [-ar ANGLE | -nr] [-v N] [--stats] [--max-elements N] [-threads N]\n"
          "                            remesh the domain of IN.mesh (or .meshb, .msh, .vtk, .obj) under the\n"
          "                            metric IN.sol (or .solb), as a background-mesh control space (-hgrad:\n"
          "                            gradation ratio dr >= 1, -1 or 0: off); without -sol: isotropic sizes,\n"
          "                            -hsiz H everywhere or the input's edge lengths clamped to [-hmin, -hmax];\n"
          "                            -hausd H: the boundary between corners becomes a smooth curve through\n"
          "                            the input's boundary vertices, re-discretized under the metric within\n"
          "                            the distance H of it (without: the input's boundary edges are kept);\n"
          "                            -ar ANGLE: boundary turns above ANGLE degrees are corners (default 45),\n"
          "                            -nr: no angle corners (reference changes and ends only);\n"
          "                            -in / -out as in MMG; -v 1: also per-stage wall and CPU seconds and\n"
          "                            peak RSS on stderr; -threads N: worker threads (the same output for any N)\n",
          runRemesh};
}

}  // namespace anisomesh::cli

// Native twin of native/bench/surface_drag.mjs: the page worker's surface meshCase call
// (runCase with stats: false, elementMeasures: false, patchParams: true, as while a handle
// is held) on a surface case whose first patch gets a radial source moved by 0.1 in u per
// run, as a drag moves it. One process, so the curvature-stage cache works as in the
// worker. Prints CPU and wall ms per run and the median of the runs after the first; a
// profiler (perf record -g) run on it shows where a drag's time goes. Each run's line ends
// with a hash of its mesh (two builds' meshes compared run for run).
//
// Freed memory is kept for reuse (as the CLI does, and as a wasm instance's memory always
// is): glibc's default hands large freed blocks back to the kernel and each run then pays
// page faults for them again, 25 % of a refined run's CPU on this virtual machine, which
// the worker never pays. --return-memory keeps glibc's default.
//
// Usage: surface_drag_native CASE.json [RUNS] [--hmax H --chord T] [--report] [--threads N] [--return-memory]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#endif

#include "anisomesh/core/parallel.h"
#include "anisomesh/io/run_case.h"

namespace {
double cpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * double(ts.tv_sec) + 1e-6 * double(ts.tv_nsec);
}
double wallMs() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
// FNV-1a over the mesh's points, parameters, triangles, quads and refs (bits exact): tells
// whether two builds give the same meshes run for run.
unsigned long long meshHash(const anisomesh::Mesh& m) {
  unsigned long long h = 1469598103934665603ull;
  auto add = [&](const void* p, size_t n) {
    const unsigned char* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  for (const auto& p : m.points) add(p.data(), 3 * sizeof(double));
  for (const auto& p : m.params) add(p.data(), 2 * sizeof(double));
  add(m.triangles.data(), m.triangles.size() * sizeof(m.triangles[0]));
  add(m.quads.data(), m.quads.size() * sizeof(m.quads[0]));
  add(m.pointRefs.data(), m.pointRefs.size() * sizeof(int));
  add(m.triangleRefs.data(), m.triangleRefs.size() * sizeof(int));
  return h;
}
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: surface_drag_native CASE.json [RUNS] [--hmax H] [--chord T] [--report] [--threads N] "
                 "[--return-memory]\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream ss;
  ss << in.rdbuf();
  nlohmann::json c = nlohmann::json::parse(ss.str());
  int runs = 8;
  bool report = false, keepMemory = true;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--hmax" && i + 1 < argc)
      c["metric"]["hmax"] = std::stod(argv[++i]);
    else if (a == "--chord" && i + 1 < argc)
      c["metric"]["chordTolerance"] = std::stod(argv[++i]);
    else if (a == "--report")
      report = true;
    else if (a == "--threads" && i + 1 < argc)
      anisomesh::setThreadCount(std::stoi(argv[++i]));
    else if (a == "--return-memory")
      keepMemory = false;
    else
      runs = std::stoi(a);
  }
#if defined(__linux__) && defined(__GLIBC__)
  if (keepMemory) {  // the CLI's settings (native/cli/huge_pages.cpp)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
  }
#endif
  anisomesh::RunCaseOptions o;
  o.stats = false;
  o.elementMeasures = false;
  o.patchParams = true;
  std::vector<double> cpu, wall, rep, repWall;
  size_t tris = 0;
  for (int k = 0; k < runs; ++k) {
    c["patches"][0]["sources"] = nlohmann::json::array({{{"type", "radial"},
                                                         {"center", {0.1 * k, 0.0}},
                                                         {"metric", {{"alpha", 0.0}, {"h1", 0.15}, {"h2", 0.15}}},
                                                         {"radius", 1.5}}});
    const std::string text = c.dump();
    const double c0 = cpuMs(), w0 = wallMs();
    anisomesh::CaseRun run = anisomesh::runCase(text, o);
    cpu.push_back(cpuMs() - c0);
    wall.push_back(wallMs() - w0);
    tris = run.mesh.triangles.size();
    if (report) {
      const double r0 = cpuMs(), rw = wallMs();
      anisomesh::measureSurfaceElements(*run.surfaceReport);
      (void)anisomesh::caseRunStats(run);
      rep.push_back(cpuMs() - r0);
      repWall.push_back(wallMs() - rw);
    }
    std::printf("run %d: %zu triangles, CPU %.1f ms (wall %.1f), mesh %016llx\n", k, tris, cpu.back(), wall.back(),
                meshHash(run.mesh));
  }
  std::printf("%s: %zu triangles: first CPU %.1f ms, later median CPU %.1f ms (wall %.1f)", argv[1], tris, cpu[0],
              median({cpu.begin() + 1, cpu.end()}), median({wall.begin() + 1, wall.end()}));
  if (report) std::printf(", report after: median CPU %.1f ms (wall %.1f)", median(rep), median(repWall));
  std::printf(keepMemory ? " [freed memory kept]" : " [freed memory returned]");
  std::printf("\n");
  return 0;
}

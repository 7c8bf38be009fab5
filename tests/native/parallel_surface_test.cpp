// Surfaces on several threads: the curvature stage's samples taken concurrently, patches
// meshed concurrently, a large patch's parts meshed concurrently, and the report's tallies
// kept per thread slot (core/parallel.h). The rule: the same mesh and the same report
// (timings aside) for any thread count.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/io/run_case.h"

using namespace anisomesh;

namespace {

struct SurfaceThreadsGuard {
  int saved = threadCount();
  ~SurfaceThreadsGuard() { setThreadCount(saved); }
};

nlohmann::json exampleCase(const std::string& name) {
  std::ifstream in(std::string(ANISOMESH_SOURCE_DIR) + "/examples/surface/" + name);
  std::stringstream ss;
  ss << in.rdbuf();
  return nlohmann::json::parse(ss.str());
}

// A run's mesh (its bits, hashed) and its report without its clock readings.
struct RunText {
  size_t meshHash = 0;
  std::string report;
};

RunText runText(const nlohmann::json& c) {
  const CaseRun run = runCase(c.dump(), RunCaseOptions{});
  nlohmann::json stats = run.stats;
  for (const char* k : {"secondsTotal", "controlSpaceSeconds", "curvatureSeconds"}) stats.erase(k);
  std::ostringstream os;
  os.precision(17);
  for (const Vec3& p : run.mesh.points) os << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const auto& t : run.mesh.triangles) os << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  for (const auto& q : run.mesh.quads) os << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << '\n';
  return {std::hash<std::string>{}(os.str()), stats.dump()};
}

// The case on `threads` threads, its curvature stage built afresh: an element budget of its
// own (far above the mesh) gives the stage a key of its own, so no earlier run's is reused.
RunText runFresh(nlohmann::json c, int threads) {
  setThreadCount(threads);
  c["options"]["maxElements"] = 40000000 + 64 * threads;
  return runText(c);
}

void expectTheSameForAnyThreadCount(const nlohmann::json& c) {
  SurfaceThreadsGuard guard;
  const RunText one = runFresh(c, 1);
  EXPECT_NE(one.report.find("\"controlSpaceQueries\""), std::string::npos);
  EXPECT_NE(one.report.find("\"curvatureEvaluations\""), std::string::npos);
  for (int threads : {2, 4}) {
    const RunText other = runFresh(c, threads);
    EXPECT_EQ(other.meshHash, one.meshHash) << threads << " threads";
    EXPECT_EQ(other.report, one.report) << threads << " threads";
  }
}

}  // namespace

// Two patches with a shared curve: meshed side by side from 2 threads on.
TEST(ParallelSurface, TwoPatchModelTheSameForAnyThreadCount) {
  expectTheSameForAnyThreadCount(exampleCase("surface_two_patch_c.json"));
}

// One patch of about 53k triangles: its domain is split into parts meshed concurrently,
// each querying the counting view of the patch's control space (about 420k queries).
TEST(ParallelSurface, LargePatchPartsTheSameForAnyThreadCount) {
  nlohmann::json c = exampleCase("surface_p2_holes.json");
  c["metric"]["hmax"] = 0.3;
  c["metric"]["chordTolerance"] = 0.0025;
  expectTheSameForAnyThreadCount(c);
}

// Threads alive at once hold distinct slots; a region nested in a multi-threaded one runs
// on its caller's thread.
TEST(ParallelSurface, ThreadSlotsDistinctAndNestedRegionsStayOnTheirThread) {
  SurfaceThreadsGuard guard;
  setThreadCount(4);
  std::mutex m;
  std::set<std::thread::id> threads;
  std::set<int> slots;
  bool nestedMoved = false, nestedOutside = false;
  std::vector<char> arrived(4, 0);
  // Four chunks that wait for each other: all four threads are alive together.
  parallelChunks(4, 1, [&](size_t chunk, size_t, size_t) {
    {
      std::lock_guard<std::mutex> lock(m);
      threads.insert(std::this_thread::get_id());
      slots.insert(threadSlot());
      arrived[chunk] = 1;
    }
    for (bool all = false; !all;) {
      std::this_thread::yield();
      std::lock_guard<std::mutex> lock(m);
      all = arrived == std::vector<char>(4, 1);
    }
    const std::thread::id self = std::this_thread::get_id();
    const int slot = threadSlot();
    parallelChunks(8, 1, [&](size_t, size_t, size_t) {
      std::lock_guard<std::mutex> lock(m);
      if (std::this_thread::get_id() != self || threadSlot() != slot) nestedMoved = true;
      if (!insideParallelChunks()) nestedOutside = true;
    });
  });
  EXPECT_EQ(threads.size(), 4u);
  EXPECT_EQ(slots.size(), threads.size());
  for (int s : slots) EXPECT_TRUE(s >= 0 && s < kThreadSlots) << s;
  EXPECT_FALSE(nestedMoved);
  EXPECT_FALSE(nestedOutside);
  EXPECT_FALSE(insideParallelChunks());
  EXPECT_EQ(threadSlot(), 0);
}

// parallelInvoke's first branch runs on the caller while the second's thread lives: its
// own regions stay on the caller (else threadCount() + 1 threads: in the pthreads build one
// more than the pool, a thread that would never start).
TEST(ParallelSurface, RegionsInParallelInvokesFirstBranchStayOnTheCaller) {
  SurfaceThreadsGuard guard;
  setThreadCount(4);
  const std::thread::id caller = std::this_thread::get_id();
  std::mutex m;
  std::set<std::thread::id> inA;
  parallelInvoke(
      [&] {
        parallelChunks(16, 1, [&](size_t, size_t, size_t) {
          {
            std::lock_guard<std::mutex> lock(m);
            inA.insert(std::this_thread::get_id());
          }
          // Long enough chunks that started threads would take some.
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
        });
      },
      [] {});
  EXPECT_EQ(inA, std::set<std::thread::id>{caller});
  EXPECT_FALSE(insideParallelChunks());
}

// Patches meshed concurrently report progress from the calling thread only (a JS callback
// in the pthreads build must stay on its thread), and a false answer cancels the run.
TEST(ParallelSurface, ProgressFromTheCallingThreadAndCancels) {
  SurfaceThreadsGuard guard;
  setThreadCount(2);
  nlohmann::json c = exampleCase("surface_two_patch_c.json");
  const std::thread::id self = std::this_thread::get_id();
  std::mutex m;
  int calls = 0, elsewhere = 0;
  RunCaseOptions o;
  o.progress = [&](double) {
    std::lock_guard<std::mutex> lock(m);
    ++calls;
    if (std::this_thread::get_id() != self) ++elsewhere;
    return true;
  };
  (void)runCase(c.dump(), o);
  EXPECT_GT(calls, 0);
  EXPECT_EQ(elsewhere, 0);
  // Cancelled at the third report: the run stops with ErrorCode::Cancelled.
  int answered = 0;
  o.progress = [&](double) { return ++answered < 3; };
  try {
    (void)runCase(c.dump(), o);
    ADD_FAILURE() << "not cancelled";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Cancelled) << e.what();
  }
}

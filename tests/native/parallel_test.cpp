// The parallel layer (core/parallel.h) and the rule it serves: the same input gives the
// same mesh, file bytes and report for any thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "anisomesh/core/parallel.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/report_json.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/pipeline/pipeline.h"

using namespace anisomesh;

namespace {

// Restores the thread count when a test ends.
struct ThreadCountGuard {
  int saved = threadCount();
  ~ThreadCountGuard() { setThreadCount(saved); }
};

// An 81 x 81 grid of the unit square with a boundary-layer metric (about 40k triangles out).
void layerCarrier(Mesh* m, std::vector<Metric>* metrics) {
  const int n = 80;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      m->points.push_back(Vec3(x, y, 0));
      const double hy = std::min(0.008, 0.001 + 0.2 * std::abs(y - 0.5));
      metrics->push_back(Metric::fromSizes(0.0, 0.008, hy));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      m->triangles.push_back({a, a + 1, a + n + 2});
      m->triangles.push_back({a, a + n + 2, a + n + 1});
    }
}

}  // namespace

TEST(Parallel, ChunksCoverEveryItemOnceForAnyThreadCount) {
  ThreadCountGuard guard;
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    std::vector<std::atomic<int>> hits(10007);
    std::vector<size_t> chunkOf(10007, 99999);
    parallelChunks(hits.size(), 1000, [&](size_t chunk, size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) ++hits[i], chunkOf[i] = chunk;
    });
    for (size_t i = 0; i < hits.size(); ++i) {
      ASSERT_EQ(hits[i], 1) << i;
      ASSERT_EQ(chunkOf[i], i / 1000) << i;  // chunk boundaries from the size only
    }
    EXPECT_EQ(chunkCount(10007, 1000), 11u);
  }
}

TEST(Parallel, TheLowestFailingChunkIsRethrown) {
  ThreadCountGuard guard;
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    try {
      parallelChunks(100, 1, [](size_t chunk, size_t, size_t) {
        if (chunk == 37 || chunk == 80) throw std::runtime_error("chunk " + std::to_string(chunk));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "chunk 37");
    }
    int order = 0;
    EXPECT_THROW(parallelInvoke([&] { order += 1; }, [] { throw std::runtime_error("b"); }), std::runtime_error);
    EXPECT_EQ(order, 1);  // a ran even though b failed
  }
}

// Same remesh, same Medit bytes and the same quality report with 1, 2 and 4 threads
// (writing and the report's metric queries run in chunks of 16384 lines / 4096 vertices).
TEST(Parallel, RemeshOutputIdenticalForOneTwoAndFourThreads) {
  ThreadCountGuard guard;
  Mesh carrier;
  std::vector<Metric> metrics;
  layerCarrier(&carrier, &metrics);
  std::string first, firstReport;
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    PipelineReport report;
    std::unique_ptr<AdaptiveControlSpace> cs;
    const Mesh out = remesh(carrier, metrics, RemeshOptions{}, &report, &cs);
    ASSERT_GT(out.points.size(), 16384u);  // several writing chunks
    const std::string text = writeMedit(out);
    nlohmann::json q = qualityReportToJson(measureQuality(out, *cs));
    q.erase("timings");
    if (threads == 1) {
      first = text, firstReport = q.dump();
      continue;
    }
    EXPECT_EQ(text, first) << threads << " threads";
    EXPECT_EQ(q.dump(), firstReport) << threads << " threads";
  }
}

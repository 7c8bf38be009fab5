// The parallel layer (core/parallel.h) and the rule it serves: the same input gives the
// same mesh, file bytes and report for any thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/report_json.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/pipeline/mesh_statistics.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/pipeline/remesh_geometry.h"

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

// The offset of the start of line `line` (1-based) of text.
size_t lineStart(const std::string& text, int line) {
  size_t at = 0;
  for (int l = 1; l < line; ++l) at = text.find('\n', at) + 1;
  return at;
}

}  // namespace

// Sections of many records (read in parallel text blocks of 256 KiB, batches of 4 MiB)
// give the values of the token-by-token reading for any thread count: one per line, a
// record split over two lines (the section falls back), no newline after the last record,
// and an error's message names its line.
TEST(Parallel, LargeSectionsReadTheSameForAnyThreadCount) {
  ThreadCountGuard guard;
  Mesh m;
  m.dimension = 2;
  const int n = 200000;  // about 8 MB of vertices: several batches
  for (int i = 0; i < n; ++i) {
    m.points.push_back(Vec3(std::sqrt(double(i)) * 1e-3, 1.0 / (i + 1), 0));
    m.pointRefs.push_back(i % 7);
  }
  for (int i = 0; i + 2 < n; i += 3) {
    m.triangles.push_back({i, i + 1, i + 2});
    m.triangleRefs.push_back(i % 5);
  }
  const std::string text = writeMedit(m);
  // Vertex i (1-based) is on line 5 + i.
  std::string split = text;
  split[split.find(' ', lineStart(split, 5 + 150000))] = '\n';
  std::string unterminated = text.substr(0, text.rfind("End"));
  unterminated.pop_back();  // the last triangle's newline
  std::string broken = text;
  const size_t at = broken.find(' ', lineStart(broken, 5 + 170001)) + 1;
  broken.replace(at, broken.find(' ', at) - at, "x");
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    for (const std::string* t :
         {&text, static_cast<const std::string*>(&split), static_cast<const std::string*>(&unterminated)}) {
      const Mesh back = parseMedit(*t);
      ASSERT_EQ(back.points.size(), m.points.size()) << threads;
      EXPECT_EQ(std::memcmp(back.points.data(), m.points.data(), m.points.size() * sizeof(Vec3)), 0) << threads;
      EXPECT_EQ(back.pointRefs, m.pointRefs) << threads;
      EXPECT_EQ(back.triangles, m.triangles) << threads;
      EXPECT_EQ(back.triangleRefs, m.triangleRefs) << threads;
    }
    try {
      parseMedit(broken);
      ADD_FAILURE() << "no error, " << threads << " threads";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("line " + std::to_string(5 + 170001) + ":"), std::string::npos) << e.what();
    }
  }
}

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

namespace {

// A grid of about 103k vertices (more than one chunk of the report's parallel loops, which
// take 65,536) whose rows shrink towards the top, fastest in the last rows: the largest
// neighbour size ratio (about 1.68) lies in the last chunk of vertices.
Mesh gradedGrid() {
  Mesh m;
  const int n = 320;
  std::vector<double> ys(n + 1);
  // (+1e-6 j: the top row keeps a positive height.)
  for (int j = 0; j <= n; ++j) ys[j] = 1.0 - std::pow(1.0 - double(j) / n, 2.0) + 1e-6 * j;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.points.push_back(Vec3(double(i) / n, ys[j], 0));
  const auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // The diagonal alternates: vertex buckets of different shapes.
      if ((i + j) % 2) {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        m.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return m;
}

}  // namespace

// largestNeighbourSizeRatio works in chunks of 65,536 vertices: on gradedGrid(), whose
// largest ratio lies in the last chunk, it equals a plain per-edge map for 1, 2 and 4 threads.
TEST(Parallel, NeighbourSizeRatioOverChunksMatchesAPlainEdgeMap) {
  ThreadCountGuard guard;
  const Mesh m = gradedGrid();
  // Reference: the first owner of each edge against every later one, through a std::map.
  std::map<std::pair<int, int>, std::vector<double>> owners;
  for (const auto& t : m.triangles) {
    const Vec3 a = m.points[t[0]], b = m.points[t[1]], c = m.points[t[2]];
    const double size =
        std::sqrt(std::abs(0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()))));
    for (int k = 0; k < 3; ++k)
      owners[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}].push_back(size);
  }
  double expected = 1.0;
  for (const auto& [edge, sizes] : owners)
    for (size_t k = 1; k < sizes.size(); ++k)
      expected = std::max(expected, std::max(sizes[0], sizes[k]) / std::min(sizes[0], sizes[k]));
  ASSERT_GT(expected, 1.01);
  ASSERT_GT(m.points.size(), size_t(65536));
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    EXPECT_EQ(largestNeighbourSizeRatio(m), expected) << threads << " threads";
  }
}

// distinctElementEdges sorts and writes its buckets in chunks of 65,536 vertices: on
// gradedGrid() it gives the edges of a std::set, in (a, b) order, for 1, 2 and 4 threads.
TEST(Parallel, DistinctElementEdgesOverChunksMatchAnOrderedSet) {
  ThreadCountGuard guard;
  const Mesh m = gradedGrid();
  std::set<std::array<int, 2>> reference;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) reference.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  const std::vector<std::array<int, 2>> expected(reference.begin(), reference.end());
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    EXPECT_EQ(distinctElementEdges(m), expected) << threads << " threads";
  }
}

// boundaryLoopsFromMesh counts and places the element edges in their buckets per range of
// elements, one per thread: on a frame one cell wide (a 64 x 64 grid's border cells: every
// vertex is on the outer loop or the hole's) whose vertices are numbered at random, so
// that every range's edges fall in buckets all over, the loops are those of one thread
// for 2, 3 and 4 threads.
TEST(Parallel, BoundaryLoopsFromMeshTheSameForAnyThreadCount) {
  ThreadCountGuard guard;
  const int n = 64;
  auto onFrame = [&](int i, int j) { return i <= 1 || j <= 1 || i >= n - 1 || j >= n - 1; };
  std::vector<int> id(size_t((n + 1) * (n + 1)), -1);
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      if (onFrame(i, j)) id[size_t(j * (n + 1) + i)] = int(m.points.size()), m.points.push_back(Vec3(i, j, 0));
  std::vector<int> shuffled(m.points.size());
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(14));
  const std::vector<Vec3> points = m.points;
  for (size_t k = 0; k < points.size(); ++k) m.points[size_t(shuffled[k])] = points[k];
  auto v = [&](int i, int j) { return shuffled[size_t(id[size_t(j * (n + 1) + i)])]; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i > 0 && j > 0 && i < n - 1 && j < n - 1) continue;  // the hole
      m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  for (int i = 0; i < n; ++i) m.edges.push_back({v(i, 0), v(i + 1, 0)}), m.edgeRefs.push_back(3);
  setThreadCount(1);
  const std::vector<BoundaryLoop> expected = boundaryLoopsFromMesh(m);
  ASSERT_EQ(expected.size(), 2u);
  EXPECT_EQ(expected[0].points.size() + expected[1].points.size(), m.points.size());
  for (int threads : {2, 3, 4}) {
    setThreadCount(threads);
    const std::vector<BoundaryLoop> loops = boundaryLoopsFromMesh(m);
    ASSERT_EQ(loops.size(), expected.size()) << threads << " threads";
    for (size_t l = 0; l < loops.size(); ++l) {
      EXPECT_EQ(loops[l].points, expected[l].points) << threads << " threads, loop " << l;
      EXPECT_EQ(loops[l].edgeRefs, expected[l].edgeRefs) << threads << " threads, loop " << l;
    }
  }
}

// Bounded work on hostile input (issue 15), unit level: number overflow in JSON named by
// its path, the control-space node budget and cancellation, the element estimate made
// before discretization, allocation failures as OutOfMemory, bounded file reading, and
// removal of the temporaries a killed write leaves; the contour estimate from the polyline
// vertices and the crossing search behind polyline_1m.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "anisomesh/boundary/discretize.h"
#include "anisomesh/controlspace/background_mesh_control_space.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/geometry/curve.h"
#include "anisomesh/geometry/domain.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/json_text.h"
#include "anisomesh/io/run_case.h"
#include "anisomesh/pipeline/element_estimate.h"
#include "anisomesh/pipeline/mesh_metric_field.h"

namespace anisomesh {
namespace {

const char* kHostileSquare =
    R"("domain": {"outer": [{"type": "polyline", "points": [[0,0],[1,0],[1,1],[0,1],[0,0]]}]})";

ErrorCode hostileCodeOf(const std::function<void()>& f, std::string* message = nullptr) {
  try {
    f();
  } catch (const Error& e) {
    if (message) *message = e.what();
    return e.code();
  }
  ADD_FAILURE() << "no anisomesh::Error thrown";
  return ErrorCode::Internal;
}

TEST(JsonOverflow, PathOfTheOverflowingNumber) {
  EXPECT_EQ(jsonOverflowPath(R"({"a": 1, "b": {"c": [1, 2, 1e999]}})"), "b.c[2]");
  EXPECT_EQ(jsonOverflowPath(R"({"s": [{"x": 1}, {"y": [0, -1e400]}]})"), "s[1].y[1]");
  EXPECT_EQ(jsonOverflowPath("1e999"), "(root)");
  EXPECT_EQ(jsonOverflowPath(R"({"a": 1e300})"), "");
}

TEST(JsonOverflow, CaseRunGivesParseErrorNamingThePath) {
  std::string msg;
  EXPECT_EQ(hostileCodeOf([&] { runCase(std::string("{") + kHostileSquare + R"(, "controlSpace": {"hmax": 1e999}})"); },
                          &msg),
            ErrorCode::ParseError);
  EXPECT_NE(msg.find("controlSpace.hmax"), std::string::npos) << msg;
  // Surface cases go through the other reader.
  EXPECT_EQ(hostileCodeOf([&] { runCase(R"({"patches": [], "metric": {"hmax": -1e999}})"); }, &msg),
            ErrorCode::ParseError);
  EXPECT_NE(msg.find("metric.hmax"), std::string::npos) << msg;
}

// A unit square control space refined everywhere, as far as its levels allow.
TEST(ControlSpaceBudget, RefinementStopsAtTheNodeBudgetBeforeTheWork) {
  QuadtreeOptions o;
  o.maxLevel = 20;
  QuadtreeControlSpace cs(Box2{{0, 0}, {1, 1}}, o);
  ControlSpaceLimits limits;
  limits.maxNodes = 5000;
  cs.setLimits(limits);
  std::string msg;
  EXPECT_EQ(hostileCodeOf([&] { cs.refine([](const ControlElement&) { return true; }, nullptr); }, &msg),
            ErrorCode::ElementBudgetExceeded);
  EXPECT_NE(msg.find("control-space refinement"), std::string::npos) << msg;
  EXPECT_NE(msg.find("node budget of 5000"), std::string::npos) << msg;
  EXPECT_LE(cs.nodeCount(), 5000);  // the estimate came before the batch that would pass it
  // The background mesh too.
  BackgroundMeshControlSpace bg(Box2{{0, 0}, {1, 1}});
  bg.setLimits(limits);
  EXPECT_EQ(hostileCodeOf([&] { bg.refine([](const ControlElement&) { return true; }, nullptr); }),
            ErrorCode::ElementBudgetExceeded);
  EXPECT_LE(bg.nodeCount(), 2 * 5000);  // bisection's conforming closure may add more than one node per split
  // The clone keeps the budget.
  EXPECT_EQ(cs.clone()->limits().maxNodes, 5000);
}

TEST(ControlSpaceBudget, DerivedFromTheElementBudget) {
  EXPECT_EQ(controlSpaceNodeBudget(50000000), 50000000 / 64 + 262144);
  // A case with maxLevel 20 and a fine oscillating field stops in the control space.
  RunCaseOptions opt;
  opt.maxControlNodes = 20000;
  std::string msg;
  EXPECT_EQ(hostileCodeOf(
                [&] {
                  runCase(std::string("{") + kHostileSquare +
                              R"J(, "controlSpace": {"hmax": 0.1, "maxLevel": 20, "refineThreshold": 0.001},
                              "sources": [{"type": "analytic", "field": "expression", "h1": "0.001 + 0.05 * abs(sin(40 * x) * sin(40 * y))"}]
})J",
                          opt);
                },
                &msg),
            ErrorCode::ElementBudgetExceeded);
  EXPECT_NE(msg.find("node budget of 20000"), std::string::npos) << msg;
}

TEST(ControlSpaceBudget, ProgressDuringRefinementCancels) {
  QuadtreeOptions o;
  o.maxLevel = 12;
  QuadtreeControlSpace cs(Box2{{0, 0}, {1, 1}}, o);
  ControlSpaceLimits limits;
  int calls = 0;
  limits.progress = [&](double) { return ++calls < 2; };
  cs.setLimits(limits);
  EXPECT_EQ(hostileCodeOf([&] { cs.refine([](const ControlElement&) { return true; }, nullptr); }),
            ErrorCode::Cancelled);
  EXPECT_EQ(calls, 2);
}

// The check skips the estimate when elementCountBound() is within the budget: the bound
// must never be below the estimate, with either interpolation and sizes that jump from
// node to node (serendipity weights go negative there).
TEST(ElementEstimate, BoundIsNeverBelowTheEstimate) {
  Domain square;
  square.outer.add(std::make_shared<PolylineCurve>(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}));
  for (const auto interp : {QuadtreeInterpolation::Bilinear, QuadtreeInterpolation::Serendipity}) {
    QuadtreeOptions o;
    o.interpolation = interp;
    QuadtreeControlSpace cs(Box2{{-0.01, -0.01}, {1.01, 1.01}}, o);
    cs.refine([](const ControlElement& e) { return e.size > 0.02 && e.box.center().x() < 0.4; }, nullptr);
    for (int i = 0; i < cs.nodeCount(); ++i) {
      const Vec2 p = cs.nodePosition(i);
      const double h = (i % 3 == 0) ? 0.002 : 0.05 + 0.1 * p.y();  // fine and coarse nodes side by side
      cs.setNodeMetric(i, Metric::fromSizes(3.0 * p.x(), h, 4.0 * h));
    }
    cs.applyConstraints();
    const double estimate = estimateElementCount(square, cs), bound = elementCountBound(cs);
    EXPECT_GT(estimate, 0.0);
    EXPECT_LE(estimate, bound) << int(interp);
    EXPECT_LT(bound, 1000.0 * estimate) << int(interp);  // a bound, not infinity
    // Above the bound's budget the estimate is not made; below it, the check still refuses.
    EXPECT_NO_THROW(checkElementEstimate(square, cs, std::int64_t(bound), "a stage"));
    EXPECT_EQ(hostileCodeOf([&] { checkElementEstimate(square, cs, std::int64_t(estimate / 4), "a stage"); }),
              ErrorCode::ElementBudgetExceeded);
  }
}

TEST(ElementEstimate, MetricAreaOverUnitTriangles) {
  QuadtreeControlSpace cs(Box2{{-0.01, -0.01}, {1.01, 1.01}});
  for (int i = 0; i < cs.nodeCount(); ++i) cs.setNodeMetric(i, Metric::isotropic(0.01));
  Domain square;
  square.outer.add(std::make_shared<PolylineCurve>(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}));
  const double expect = 1.0 / (0.01 * 0.01) / (std::sqrt(3.0) / 4.0);  // 23094
  // Sampled per control element (16 here, 4 of them straddling the edge): within 25%.
  EXPECT_NEAR(estimateElementCount(square, cs), expect, 0.25 * expect);
  std::string msg;
  EXPECT_EQ(hostileCodeOf([&] { checkElementEstimate(square, cs, 1000, "a stage"); }, &msg),
            ErrorCode::ElementBudgetExceeded);
  EXPECT_EQ(msg.rfind("a stage: the metric asks for about", 0), 0u) << msg;
  EXPECT_NO_THROW(checkElementEstimate(square, cs, 20000, "a stage"));  // within the slack of 2
  // hmax 1e-6 on the unit square: refused at once, no overflow in the figure.
  RunCaseOptions opt;
  EXPECT_EQ(
      hostileCodeOf([&] { runCase(std::string("{") + kHostileSquare + R"(, "controlSpace": {"hmax": 1e-6}})", opt); },
                    &msg),
      ErrorCode::ElementBudgetExceeded);
  EXPECT_NE(msg.find("element estimate before contour discretization"), std::string::npos) << msg;
  EXPECT_NE(msg.find("about 2.44e+12 elements"), std::string::npos) << msg;  // 1.057 * 1e12 / (sqrt(3) / 4)
}

TEST(OutOfMemory, AllocationFailuresBecomeCodedErrorsNamingTheStage) {
  std::string msg;
  EXPECT_EQ(hostileCodeOf([&] { withStage("a stage", [] { throw std::bad_alloc(); }); }, &msg), ErrorCode::OutOfMemory);
  EXPECT_EQ(msg, "out of memory during a stage");
  EXPECT_EQ(hostileCodeOf([&] {
              withStage("another", [] {
                std::vector<double> v;
                v.reserve(v.max_size() + 1);
              });
            }),
            ErrorCode::OutOfMemory);
  EXPECT_STREQ(errorCodeName(ErrorCode::OutOfMemory), "OUT_OF_MEMORY");
}

TEST(MetricField, VertexAtInfinityIsRefusedWithoutUndefinedBehaviour) {
  Mesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {std::numeric_limits<double>::infinity(), 1, 0}};
  m.triangles = {{0, 1, 2}};
  const std::vector<Metric> metrics(3, Metric::isotropic(0.1));
  EXPECT_EQ(hostileCodeOf([&] { TriangleMeshMetricField f(m, metrics); }), ErrorCode::InvalidDomain);
  // Finite but huge coordinates: the box size (and every barycentric determinant) overflows
  // to infinity, so no query could be answered: refused up front, with a code.
  m.points = {{-1e308, -1e308, 0}, {1e308, -1e308, 0}, {1e308, 1e308, 0}};
  EXPECT_EQ(hostileCodeOf([&] { TriangleMeshMetricField f(m, metrics); }), ErrorCode::InvalidDomain);
  // Queries far away or at NaN: no float-to-int conversion out of range (UBSan fails the
  // test otherwise); far outside answers the nearest triangle, NaN is a coded error.
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const TriangleMeshMetricField g(m, metrics);
  EXPECT_NEAR(g.metricAt(Vec2(-1e300, 0.5)).tensor()(0, 0), 100.0, 1e-9);
  EXPECT_NEAR(g.metricAt(Vec2(1e300, -1e300)).tensor()(0, 0), 100.0, 1e-9);
  EXPECT_EQ(hostileCodeOf([&] { g.metricAt(Vec2(-1e300, std::nan(""))); }), ErrorCode::InvalidArgument);
  EXPECT_EQ(hostileCodeOf([&] { g.metricAt(Vec2(std::nan(""), 1e300)); }), ErrorCode::InvalidArgument);
}

TEST(FileLimits, DevicesDirectoriesAndLargeFilesAreRefusedUpFront) {
  std::string msg;
  EXPECT_EQ(hostileCodeOf([&] { readTextFile("/dev/zero"); }, &msg), ErrorCode::IoError);
  EXPECT_NE(msg.find("device"), std::string::npos) << msg;
  EXPECT_EQ(hostileCodeOf([&] { readTextFile("/tmp"); }), ErrorCode::IoError);
  const std::string path = ::testing::TempDir() + "anisomesh_file_limit.txt";
  writeTextFileAtomic(path, std::string(100, 'x'));
  ReadFileOptions o;
  o.maxBytes = 99;
  EXPECT_EQ(hostileCodeOf([&] { readTextFile(path, o); }, &msg), ErrorCode::IoError);
  EXPECT_NE(msg.find("above the input limit of 99 bytes"), std::string::npos) << msg;
  o.maxBytes = 100;
  EXPECT_EQ(readTextFile(path, o).size(), 100u);
  const std::int64_t before = defaultMaxInputBytes();
  setDefaultMaxInputBytes(50);
  EXPECT_EQ(hostileCodeOf([&] { readTextFile(path); }), ErrorCode::IoError);
  setDefaultMaxInputBytes(before);
  EXPECT_EQ(readTextFile(path).size(), 100u);
  std::remove(path.c_str());
}

// Outputs are written in slices of at most 1 MiB at their offsets, in parallel chunks: the
// file holds the pieces in order, whole, for any thread count (pieces of every size: empty,
// small, across slice boundaries, several slices long; and one large string).
TEST(FileLimits, LargeOutputsAreWrittenWholeAndInOrderOnAnyThreadCount) {
  const std::string path = ::testing::TempDir() + "anisomesh_large_write.txt";
  std::vector<std::string> pieces;
  std::string joined;
  unsigned x = 12345u;
  for (size_t size : {size_t(0), size_t(7), size_t(1) << 20, (size_t(1) << 20) + 3, size_t(3) << 20, size_t(999),
                      (size_t(5) << 20) / 2}) {
    std::string p(size, ' ');
    for (char& c : p) c = char('a' + (x = x * 1103515245u + 12345u) % 26);
    joined += p;
    pieces.push_back(std::move(p));
  }
  const int threadsBefore = threadCount();
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    writeTextFileAtomic(path, pieces);
    EXPECT_EQ(readTextFile(path), joined) << threads << " threads, pieces";
    writeTextFileAtomic(path, joined);
    EXPECT_EQ(readTextFile(path), joined) << threads << " threads, one string";
  }
  setThreadCount(threadsBefore);
  std::remove(path.c_str());
}

TEST(FileLimits, TemporariesOfAKilledWriteAreRemovedByTheNextWrite) {
  const std::string path = ::testing::TempDir() + "anisomesh_debris.mesh";
  // A process id that no longer runs: a child that has exited and been reaped.
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  const std::string dead = path + ".tmp-" + std::to_string(child) + "-1-2";
  const std::string alive = path + ".tmp-" + std::to_string(getppid()) + "-1-2";  // a running process
  const std::string other = path + ".tmpx";
  for (const std::string& p : {dead, alive, other}) std::ofstream(p) << "partial";
  writeTextFileAtomic(path, "new");
  EXPECT_FALSE(std::ifstream(dead).good()) << "the dead writer's temporary is still there";
  EXPECT_TRUE(std::ifstream(alive).good()) << "a running writer's temporary was removed";
  EXPECT_TRUE(std::ifstream(other).good());
  std::ifstream in(path);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "new");
  for (const std::string& p : {alive, other, path}) std::remove(p.c_str());
}

// Estimate before work: a polyline keeps its vertices, so one with more vertices than
// the segment budget is refused before a single metric query (polyline_1m took 71 s).
TEST(ContourEstimate, PolylineWithMoreVerticesThanTheBudgetIsRefusedBeforeAnyQuery) {
  std::vector<Vec2> pts;
  const int n = 5000;
  for (int i = 0; i <= n; ++i) {
    const double t = 2.0 * M_PI * (i % n) / n;
    pts.emplace_back(std::cos(t), std::sin(t));
  }
  Domain d;
  d.outer.add(std::make_shared<PolylineCurve>(pts, 1));
  int queries = 0;
  const AnalyticControlSpace cs(Box2{Vec2(-2, -2), Vec2(2, 2)}, [&](const Vec2&) {
    ++queries;
    return Metric::isotropic(0.1);
  });
  DiscretizeOptions o;
  o.maxSegments = 4999;
  try {
    discretizeDomain(d, cs, o);
    FAIL() << "a 5000-vertex polyline fits a budget of 4999 segments";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ElementBudgetExceeded);
    EXPECT_NE(std::string(e.what()).find("at least 5000"), std::string::npos) << e.what();
  }
  EXPECT_EQ(queries, 0);
  o.maxSegments = 5000;  // just enough: discretized, each vertex kept
  EXPECT_EQ(discretizeDomain(d, cs, o).front().points.size(), size_t(n));
  EXPECT_GT(queries, 0);
}

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}
// Proper crossing of segments ab and cd (points in general position: no touching).
bool properCross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  return orient(a, b, c) * orient(a, b, d) < 0 && orient(c, d, a) * orient(c, d, b) < 0;
}

// The grid with a sweep per cell tests fewer pairs than every pair in a cell: it must
// still find a crossing exactly when one exists, and the pair it names must cross.
TEST(PolygonCrossing, FindsACrossingExactlyWhenEveryPairTestFindsOne) {
  std::srand(15);
  auto uniform = [] { return double(std::rand()) / RAND_MAX; };
  int crossingSets = 0, cleanSets = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Star-shaped polygons (simple) with random radii, sometimes overlapping each other.
    std::vector<std::vector<Vec2>> polygons;
    const int count = 1 + trial % 3;
    for (int k = 0; k < count; ++k) {
      const Vec2 centre(3.0 * uniform(), 3.0 * uniform());
      const int n = 3 + int(60 * uniform());
      const double r0 = 0.2 + uniform();
      std::vector<Vec2> poly;
      for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * (i + 0.5 * uniform()) / n;
        const double r = r0 * (0.6 + 0.4 * uniform());
        poly.push_back(centre + r * Vec2(std::cos(a), std::sin(a)));
      }
      if (trial % 7 == 3 && n > 4) std::swap(poly[1], poly[3]);  // a bow tie: self-crossing
      polygons.push_back(poly);
    }
    bool expected = false;
    std::vector<std::array<int, 2>> ids;  // (polygon, segment)
    for (int p = 0; p < count; ++p)
      for (int i = 0; i < int(polygons[size_t(p)].size()); ++i) ids.push_back({p, i});
    auto seg = [&](int p, int i, int end) {
      const auto& poly = polygons[size_t(p)];
      return poly[size_t((i + end) % int(poly.size()))];
    };
    for (size_t s = 0; s < ids.size() && !expected; ++s)
      for (size_t t = s + 1; t < ids.size() && !expected; ++t)
        expected = properCross(seg(ids[s][0], ids[s][1], 0), seg(ids[s][0], ids[s][1], 1), seg(ids[t][0], ids[t][1], 0),
                               seg(ids[t][0], ids[t][1], 1));
    PolygonCrossing x;
    const bool found = findPolygonCrossing(polygons, &x);
    ASSERT_EQ(found, expected) << "trial " << trial;
    if (found) {
      ++crossingSets;
      EXPECT_TRUE(properCross(seg(x.polygonA, x.segmentA, 0), seg(x.polygonA, x.segmentA, 1),
                              seg(x.polygonB, x.segmentB, 0), seg(x.polygonB, x.segmentB, 1)))
          << "trial " << trial;
    } else {
      ++cleanSets;
    }
  }
  EXPECT_GT(crossingSets, 30);
  EXPECT_GT(cleanSets, 30);
}

}  // namespace
}  // namespace anisomesh

// Inspection exports, the plain-data factory and the query cache.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/control_space_spec.h"
#include "anisomesh/controlspace/query_cache.h"
#include "anisomesh/core/error.h"
#include "anisomesh/io/control_space_export.h"

using namespace anisomesh;

namespace {

ControlSpaceSpec sampleSpec(ControlSpaceKind kind) {
  ControlSpaceSpec s;
  s.kind = kind;
  s.box.lo = Vec2(0.0, 0.0);
  s.box.hi = Vec2(2.0, 1.0);
  s.maxLevel = 9;
  s.sources.resize(2);
  s.sources[0] = RadialSource{{0.5, 0.5}, Metric::fromSizes(0.2, 0.005, 0.05), 0.05};
  s.sources[1] = PolylineSource{{{1.0, 0.2}, {1.5, 0.4}, {1.8, 0.8}}, Metric::isotropic(0.01), 0.0};
  s.gradation = 2.0;
  s.hmax = 0.2;
  return s;
}

// Counts whitespace-separated numbers after the "POINTS n double" header up to "CELLS".
void checkVtk(const std::string& vtk, int nodes, int cells) {
  std::istringstream is(vtk);
  std::string line, word;
  int points = -1, cellCount = -1, coords = 0;
  bool inPoints = false;
  while (std::getline(is, line)) {
    std::istringstream ls(line);
    ls >> word;
    if (word == "POINTS") {
      ls >> points;
      inPoints = true;
      continue;
    }
    if (word == "CELLS") {
      ls >> cellCount;
      inPoints = false;
      continue;
    }
    if (inPoints) {
      std::istringstream ns(line);
      double v;
      while (ns >> v) ++coords;
    }
  }
  EXPECT_EQ(points, nodes);
  EXPECT_EQ(coords, 3 * nodes);
  EXPECT_EQ(cellCount, cells);
  EXPECT_NE(vtk.find("TENSORS metric double"), std::string::npos);
  EXPECT_NE(vtk.find("POINT_DATA " + std::to_string(nodes)), std::string::npos);
}

}  // namespace

TEST(ControlSpaceSpec, BuildsBothStructuresWithClampsAndGradation) {
  for (auto kind : {ControlSpaceKind::Quadtree, ControlSpaceKind::BackgroundMesh}) {
    const ControlSpaceSpec spec = sampleSpec(kind);
    auto cs = buildAdaptiveControlSpace(spec);
    EXPECT_STREQ(cs->kindName(), kind == ControlSpaceKind::Quadtree ? "quadtree" : "background");
    for (int i = 0; i < cs->nodeCount(); ++i) ASSERT_LE(cs->nodeMetric(i).sizes().h2, 0.2 * (1 + 1e-12));
    const MetricSizes s = cs->metricAt({0.5, 0.5}).sizes();
    EXPECT_NEAR(s.h1, 0.005, 1e-9);
    EXPECT_NEAR(s.h2, 0.05, 1e-9);
    if (auto* qt = dynamic_cast<QuadtreeControlSpace*>(cs.get())) {
      EXPECT_TRUE(qt->isBalanced());
    }
    // Smoothing is already applied: a second pass changes nothing.
    GradationOptions g;
    g.ratio = 2.0;
    EXPECT_EQ(smoothGradation(*cs, g), 0);
  }
  // Analytic-only and empty specs.
  ControlSpaceSpec a;
  a.analytic = [](const Vec2& p) { return Metric::fromSizes(0.0, 0.1, 0.01 + 0.1 * p.y()); };
  auto ca = buildControlSpace(a);
  EXPECT_NEAR(ca->metricAt({0.5, 0.5}).sizes().h1, 0.06, 0.06 * 0.05);
  ControlSpaceSpec e;
  e.defaultMetric = Metric::isotropic(0.3);
  EXPECT_NEAR(buildControlSpace(e)->metricAt({0.2, 0.7}).sizes().h1, 0.3, 1e-12);
}

TEST(ControlSpaceSpec, RejectsBadInput) {
  auto code = [](const ControlSpaceSpec& s) {
    try {
      buildControlSpace(s);
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Internal;
  };
  ControlSpaceSpec s;
  s.gradation = 0.5;
  EXPECT_EQ(code(s), ErrorCode::InvalidArgument);
  s = ControlSpaceSpec();
  s.box.lo = Vec2(1.0, 1.0);
  s.box.hi = Vec2(0.0, 2.0);
  EXPECT_EQ(code(s), ErrorCode::InvalidDomain);
  s.kind = ControlSpaceKind::BackgroundMesh;
  EXPECT_EQ(code(s), ErrorCode::InvalidDomain);
  s = ControlSpaceSpec();
  s.sources.resize(1);
  s.sources[0] = RadialSource{{0.5, 0.5}, Metric::isotropic(0.1), -1.0};
  EXPECT_EQ(code(s), ErrorCode::InvalidArgument);
  s = ControlSpaceSpec();
  s.sources.resize(1);
  s.sources[0] = SegmentSource{{0.5, 0.5}, {0.5, 0.5}, Metric::isotropic(0.1), 0.0};
  EXPECT_EQ(code(s), ErrorCode::ZeroLengthCurve);
  s = ControlSpaceSpec();
  s.hmin = 0.5;
  s.hmax = 0.1;
  EXPECT_EQ(code(s), ErrorCode::InvalidArgument);
}

TEST(ControlSpaceCache, ReusesTheLastMetricOnlyWhenClose) {
  auto cs = buildAdaptiveControlSpace(sampleSpec(ControlSpaceKind::Quadtree));
  QueryCacheOptions o;
  o.tolerance = 0.05;
  const CachedControlSpace cached(*cs, o);
  const Vec2 p(0.5, 0.5);
  const Metric m = cached.metricAt(p);
  EXPECT_EQ(cached.misses(), 1);
  // 0.01 * h1 away along the small size: metric distance 0.01 < 0.05.
  const Metric again = cached.metricAt(p + 0.00005 * Vec2(1.0, 0.0));
  EXPECT_EQ(cached.hits(), 1);
  EXPECT_EQ(again.transform(), m.transform());
  // Far away: a fresh query equal to the inner control space.
  const Vec2 q(1.7, 0.2);
  EXPECT_EQ(cached.metricAt(q).transform(), cs->metricAt(q).transform());
  EXPECT_EQ(cached.misses(), 2);
  cached.reset();
  cached.metricAt(q);
  EXPECT_EQ(cached.misses(), 3);
  QueryCacheOptions bad;
  bad.tolerance = -1.0;
  EXPECT_THROW(CachedControlSpace(*cs, bad), Error);
  // The factory wraps when asked.
  ControlSpaceSpec spec = sampleSpec(ControlSpaceKind::BackgroundMesh);
  spec.cacheTolerance = 0.1;
  auto wrapped = buildControlSpace(spec);
  EXPECT_NE(dynamic_cast<CachedControlSpace*>(wrapped.get()), nullptr);
}

TEST(ControlSpaceExport, JsonAndVtkCountNodesAndCells) {
  for (auto kind : {ControlSpaceKind::Quadtree, ControlSpaceKind::BackgroundMesh}) {
    auto cs = buildAdaptiveControlSpace(sampleSpec(kind));
    const nlohmann::json j = controlSpaceToJson(*cs);
    EXPECT_EQ(j["nodes"].size(), static_cast<size_t>(cs->nodeCount()));
    EXPECT_EQ(j["cells"].size(), static_cast<size_t>(cs->elementCount()));
    EXPECT_EQ(j["kind"], cs->kindName());
    const auto& n0 = j["nodes"][0];
    EXPECT_EQ(n0["p"].size(), 2u);
    EXPECT_EQ(n0["m"].size(), 3u);
    EXPECT_TRUE(n0.contains("h1") && n0.contains("h2") && n0.contains("alpha"));
    if (kind == ControlSpaceKind::Quadtree) {
      EXPECT_EQ(j["boxes"].size(), static_cast<size_t>(cs->elementCount()));
      EXPECT_EQ(j["cells"][0].size(), 4u);
    } else {
      EXPECT_EQ(j["cells"][0].size(), 3u);
    }
    checkVtk(controlSpaceToVtk(*cs), cs->nodeCount(), cs->elementCount());
  }
  const nlohmann::json s =
      sampledControlSpaceToJson(UniformControlSpace(Box2{{0, 0}, {1, 1}}, Metric::isotropic(0.1)), 4, 3);
  EXPECT_EQ(s["samples"].size(), 12u);
  auto cs = buildAdaptiveControlSpace(sampleSpec(ControlSpaceKind::Quadtree));
  try {
    writeControlSpaceVtk(*cs, "/nonexistent-dir/x.vtk");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::IoError);
  }
}

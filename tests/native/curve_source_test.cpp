// Curve sources in the case format (section 2.2: c(t), t1, t2, M, r): a source along an arc
// of CASE_FORMAT.md sets its metric on the arc (between t1 and t2) and not beyond its radius.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/pipeline/pipeline.h"

using namespace anisomesh;

namespace {

CaseSpec arcSourceCase(const std::string& range) {
  return parseCaseJson(
      R"({"domain": {"outer": [{"type": "polyline", "points": [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]}]},
    "controlSpace": {"hmin": 0.001, "hmax": 0.2},
    "sources": [{"type": "curve", "curve": {"type": "arc", "center": [0.5, 0.5], "radius": 0.3,
                 "start": 0, "end": 3.141592653589793}, )" +
      range + R"("metric": {"h1": 0.01}, "radius": 0.02}]})");
}

double sizeAt(const ControlSpace& cs, const Vec2& p) { return cs.metricAt(p).sizeAlong(Vec2(1.0, 0.0)); }

}  // namespace

TEST(CurveSource, SetsItsMetricAlongTheCurveBetweenT1AndT2) {
  const CaseSpec spec = arcSourceCase(R"("t1": 0, "t2": 0.5, )");
  ASSERT_EQ(spec.sources.size(), 1u);
  EXPECT_EQ(spec.sources[0].type, SourceType::Curve);
  std::unique_ptr<AdaptiveControlSpace> cs;
  const Mesh mesh = meshCase(spec, nullptr, BoundaryUpdateOptions{}, &cs);
  ASSERT_TRUE(cs);
  EXPECT_GT(mesh.triangles.size(), 0u);
  // On the arc at t = 0.25 (angle pi/4, inside [t1, t2]): the source's size.
  const Vec2 on(0.5 + 0.3 * std::cos(0.7853981633974483), 0.5 + 0.3 * std::sin(0.7853981633974483));
  EXPECT_NEAR(sizeAt(*cs, on), 0.01, 0.002);
  // At t = 0.75 (angle 3pi/4, beyond t2) and far from the arc: much larger.
  const Vec2 beyond(0.5 + 0.3 * std::cos(2.356194490192345), 0.5 + 0.3 * std::sin(2.356194490192345));
  EXPECT_GT(sizeAt(*cs, beyond), 0.05);
  EXPECT_GT(sizeAt(*cs, Vec2(0.5, 0.1)), 0.1);
}

TEST(CurveSource, RangeIsChecked) {
  EXPECT_THROW(arcSourceCase(R"("t1": 0.6, "t2": 0.5, )"), Error);
  EXPECT_THROW(arcSourceCase(R"("t2": 1.5, )"), Error);
  EXPECT_NO_THROW(arcSourceCase(""));  // t1 = 0, t2 = 1 by default
}

// Polishing (mesh/planar/polish.cpp): after the adaptation loop, the free vertices of the
// triangles still below quality 0.8 get a compass search in metric space; then the repair
// (mesh/planar/repair.cpp) collapses a short edge of those still below 0.8, the merged
// vertex placed by the same search. Both must raise the worst triangle without giving up
// the edge lengths: the examples' figures, measured with polishing off, on, and with the
// repair.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "anisomesh/io/case_json.h"
#include "anisomesh/mesh/quality.h"
#include "anisomesh/pipeline/pipeline.h"

using namespace anisomesh;

TEST(MeshPolish, RaisesTheWorstTriangleOfTheExamples) {
  struct Expect {
    const char* name;
    double minQ;            // min Q is above this (measured, below: polishing off -> on; now)
    double edgesWithinMin;  // edges in [1/sqrt2, sqrt2]: at least this (0.001 under the off figure)
  };
  const Expect cases[] = {
      // 0.706 -> 0.801; now 0.796, edges 0.9921. The edge fraction of this case spreads over
      // 0.990-0.996 when only the boundary insertion order changes (12 orders measured).
      {"shear_layer", 0.78, 0.9895},
      {"fig7_rect_holes_dr2", 0.78, 0.9973},  // 0.631 -> 0.773; repair 0.787; now 0.800, edges 0.9986
      {"expression_field", 0.75,
       0.9961},  // 0.666 -> 0.798; now 0.791 (0.712 without the repair, at 9aed3ee), edges 0.9983
  };
  for (const Expect& e : cases) {
    SCOPED_TRACE(e.name);
    const CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + e.name + ".json");
    std::unique_ptr<AdaptiveControlSpace> cs;
    const Mesh mesh = meshCase(spec, nullptr, {}, &cs);
    const QualityReport q = measureQuality(mesh, *cs);
    EXPECT_GT(q.qualityMin, e.minQ);
    EXPECT_GE(q.edgesWithinSqrt2, e.edgesWithinMin);
    EXPECT_EQ(q.inverted, 0);
  }
}

// The shear layer with its circle moved by (0.0312, -0.0168): the frontal insertion gave up
// on triangles of metric radius above 1.5 there (Rebay's point too close to a cavity
// vertex), and the improvement could not split what was left: edges 2.71 long. With the
// circumcentre tried before giving up, the longest edge is 1.43.
TEST(MeshPolish, NoUnrefinedPocketOnAShiftedShearLayer) {
  CaseSpec spec = readCaseFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/shear_layer.json");
  ASSERT_EQ(spec.sources.size(), 1u);
  spec.sources[0].analytic.center = Vec2(0.0312, -0.0168);
  std::unique_ptr<AdaptiveControlSpace> cs;
  const Mesh mesh = meshCase(spec, nullptr, {}, &cs);
  const QualityReport q = measureQuality(mesh, *cs);
  EXPECT_LT(q.edgeLengthMax, 2.0);
  EXPECT_GT(q.qualityMin, 0.5);
  EXPECT_EQ(q.inverted, 0);
}

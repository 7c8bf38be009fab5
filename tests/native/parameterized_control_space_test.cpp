// Section 4.3: the parameterization matrix Mp stored in the control nodes and interpolated
// exactly like Mt (ParameterizedControlSpace), or computed from the surface at each query.
// The expected values are computed here from the surface itself (parameterizationMatrix at
// the leaf corners), not from the view's own arrays.
#include <gtest/gtest.h>

#include <string>

#include "anisomesh/controlspace/parameterized_control_space.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/error.h"
#include "anisomesh/geometry/surface_metric.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/surface_mesh.h"

using namespace anisomesh;

namespace {

Mat2 matOf(const SymMt& s) {
  Mat2 m;
  m << s.a, s.b, s.b, s.c;
  return m;
}

// The p2 patch of fig. 10 over [-3, 3]^2 (its parameterization varies), and its control space.
struct P2Space {
  SurfaceCaseSpec spec = parseSurfaceCaseJson(
      R"({"metric": {"chordTolerance": 0.01}, "patches": [{"surface": {"type": "p2", "domain": [[-3, -3], [3, 3]]}}]})");
  std::shared_ptr<const Surface> surface = spec.model.patches[0].surface;
  std::unique_ptr<AdaptiveControlSpace> cs = buildPatchControlSpace(spec.model.patches[0], {}, spec.options);
  ParameterizationFunction mp = [s = surface](const Vec2& uv) { return parameterizationMatrix(*s, uv); };
};

double paramRelDiff(const Mat2& a, const Mat2& b) { return (a - b).norm() / b.norm(); }

}  // namespace

// At a node the view gives back the node's metric (Mt and Mp split it exactly) and Mp
// of the surface there.
TEST(ParameterizedControlSpace, NodesKeepTheirMetricAndTheSurfacesMp) {
  P2Space s;
  const ParameterizedControlSpace view(*s.cs, s.mp, ParameterizationStorage::Stored);
  int checked = 0;
  for (int i = 0; i < s.cs->nodeCount(); i += 7) {
    if (!s.cs->nodeIsFree(i)) continue;
    const Vec2 p = s.cs->nodePosition(i);
    EXPECT_LT(paramRelDiff(view.metricAt(p).tensor(), s.cs->nodeMetric(i).tensor()), 1e-9) << i;
    EXPECT_LT(paramRelDiff(view.parameterizationAt(p), parameterizationMatrix(*s.surface, p)), 1e-12) << i;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

// Stored: inside a bilinear leaf Mp is the bilinear interpolation of the surface's Mp at
// the leaf's four corners, as Mt is of the corners' Mt (Table 1, section 4.3).
TEST(ParameterizedControlSpace, StoredMpIsInterpolatedLikeMt) {
  P2Space s;
  const auto& qt = dynamic_cast<const QuadtreeControlSpace&>(*s.cs);
  ASSERT_EQ(qt.nodesPerLeaf(), 4);
  const ParameterizedControlSpace view(*s.cs, s.mp, ParameterizationStorage::Stored);
  int checked = 0;
  for (int leaf : qt.leaves()) {
    const int* nd = qt.leafNodes(leaf);
    bool free = true;
    for (int k = 0; k < 4; ++k) free = free && qt.nodeIsFree(nd[k]);
    if (!free || (leaf % 5) != 0) continue;
    const Box2 b = qt.cellBox(leaf);
    const double e = 0.3, x = 0.6;  // (eta, xi) inside the leaf
    const double w[4] = {(1 - e) * (1 - x), e * (1 - x), e * x, (1 - e) * x};
    const Vec2 p = b.lo + Vec2(e * b.size().x(), x * b.size().y());
    Mat2 mpExpected = Mat2::Zero(), mtExpected = Mat2::Zero();
    for (int k = 0; k < 4; ++k) {
      mpExpected += w[k] * parameterizationMatrix(*s.surface, qt.nodePosition(nd[k]));
      mtExpected += w[k] * matOf(qt.nodeMt(nd[k]));
    }
    EXPECT_LT(paramRelDiff(view.parameterizationAt(p), mpExpected), 1e-12) << leaf;
    EXPECT_LT(paramRelDiff(qt.metricAt(p).transform(), mtExpected), 1e-12) << leaf;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

// Computed: Mp is the surface's at the query point itself, and the metric is Mp Mt^2 Mp
// with Mt the bilinear interpolation of the corners' tangent Mt.
TEST(ParameterizedControlSpace, ComputedMpComesFromTheSurfaceAtTheQuery) {
  P2Space s;
  const auto& qt = dynamic_cast<const QuadtreeControlSpace&>(*s.cs);
  const ParameterizedControlSpace view(*s.cs, s.mp, ParameterizationStorage::Computed);
  const Vec2 p(0.37, -1.21);
  const Mat2 mp = parameterizationMatrix(*s.surface, p);
  EXPECT_EQ(view.parameterizationAt(p), mp);
  const int leaf = qt.locateLeaf(p);
  const Box2 b = qt.cellBox(leaf);
  const double e = (p.x() - b.lo.x()) / b.size().x(), x = (p.y() - b.lo.y()) / b.size().y();
  const double w[4] = {(1 - e) * (1 - x), e * (1 - x), e * x, (1 - e) * x};
  Mat2 t = Mat2::Zero();
  for (int k = 0; k < 4; ++k) t += w[k] * matOf(view.nodeTangentMt(qt.leafNodes(leaf)[k]));
  EXPECT_LT(paramRelDiff(view.metricAt(p).tensor(), mp * t * t * mp), 1e-12);
  // Node tangent Mt = sqrt(Mp^-1 M Mp^-1), from the surface's Mp at the node.
  const int n = qt.leafNodes(leaf)[0];
  const Mat2 pn = parameterizationMatrix(*s.surface, qt.nodePosition(n)), tn = matOf(view.nodeTangentMt(n));
  EXPECT_LT(paramRelDiff(pn * tn * tn * pn, qt.nodeMetric(n).tensor()), 1e-9);
}

TEST(ParameterizedControlSpace, FoldedIsNotAView) {
  P2Space s;
  EXPECT_THROW(ParameterizedControlSpace(*s.cs, s.mp, ParameterizationStorage::Folded), Error);
}

// The three storages through the case format: each a valid mesh of nearly the same
// quality (the paper: "without visible degradation"); an unknown name is refused.
TEST(ParameterizedControlSpace, CaseOptionSelectsTheStorage) {
  const std::string base = std::string(R"({"metric": {"chordTolerance": 0.01, "hmin": 0.001, "hmax": 0.6},
    "patches": [{"name": "cap", "surface": {"type": "sphere", "radius": 1.0},
                 "outer": [{"type": "polyline", "points": [[0.2, -1.0], [2.8, -1.0], [2.8, 1.0], [0.2, 1.0], [0.2, -1.0]]}]}],
    "options": {"parameterization": )");
  SurfaceMeshReport folded, stored, computed;
  const Mesh mf = meshSurfaceCase(parseSurfaceCaseJson(base + R"("folded"}})"), &folded);
  const Mesh ms = meshSurfaceCase(parseSurfaceCaseJson(base + R"("stored"}})"), &stored);
  const Mesh mc = meshSurfaceCase(parseSurfaceCaseJson(base + R"("computed"}})"), &computed);
  ASSERT_GT(mf.triangles.size(), 200u);
  for (const SurfaceMeshReport* r : {&stored, &computed}) {
    EXPECT_NEAR(r->quality.qualityMean, folded.quality.qualityMean, 0.03);
    EXPECT_NEAR(r->quality.edgesWithinSqrt2, folded.quality.edgesWithinSqrt2, 0.05);
    EXPECT_GT(r->quality.qualityMin, 0.2);
  }
  EXPECT_NE(ms.points, mf.points);  // the storages really answer differently
  try {
    parseSurfaceCaseJson(base + R"("cached"}})");
    FAIL() << "accepted an unknown storage";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ParseError);
    EXPECT_NE(std::string(e.what()).find("options.parameterization"), std::string::npos) << e.what();
  }
}

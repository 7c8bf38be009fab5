// What the surface remesh path reuses or shortens must not change a bit: first-order
// surface derivatives against the full ones, surface identities (the key of the
// curvature-stage cache), and repeated runs of a case with a moved source.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "anisomesh/geometry/surface.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/run_case.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/surface_mesh.h"

namespace {

using namespace anisomesh;

std::uint64_t bitsOf(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

void expectSameBits(const Vec3& a, const Vec3& b, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_EQ(bitsOf(a[k]), bitsOf(b[k])) << what << " [" << k << "]";
}

std::array<std::array<Vec3, 4>, 4> bumpGrid(double lift) {
  std::array<std::array<Vec3, 4>, 4> cp;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      cp[i][j] = Vec3(i / 3.0, j / 3.0, (i == 1 || i == 2) && (j == 1 || j == 2) ? lift : 0.0);
  return cp;
}

std::vector<std::shared_ptr<const Surface>> everyKind() {
  std::vector<std::vector<Vec3>> bs(5, std::vector<Vec3>(5));
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) bs[i][j] = Vec3(i / 4.0, j / 4.0, 0.1 * ((i * 7 + j * 3) % 5));
  return {
      std::make_shared<PlaneSurface>(Vec3(1, 2, 3), Vec3(1, 0.5, 0), Vec3(0, 1, 0.25)),
      std::make_shared<HeightFieldSurface>("sin(u)*cos(2*v) + u^3", Box2{{-1, -1}, {1, 1}}),
      std::make_shared<CylinderSurface>(1.5),
      std::make_shared<SphereSurface>(2.0),
      std::make_shared<TorusSurface>(3.0, 1.0),
      std::make_shared<BezierPatchSurface>(bumpGrid(0.5)),
      std::make_shared<BSplinePatchSurface>(bs),
      std::make_shared<ExpressionSurface>("u*cos(v)", "u*sin(v)", "sqrt(1 + u^2) + (1 + u)^v",
                                          Box2{{0.5, 0}, {2, 6.283185307179586}}),
      paperP2(),
  };
}

// firstDerivatives() is S, Su, Sv with derivatives()' bits, on every kind of surface.
TEST(SurfaceReuse, FirstDerivativesHaveTheBitsOfTheFullOnes) {
  std::mt19937_64 rng(11);
  for (const auto& s : everyKind()) {
    const Box2 b = s->domain();
    std::uniform_real_distribution<double> du(b.lo.x(), b.hi.x()), dv(b.lo.y(), b.hi.y());
    for (int k = 0; k < 100; ++k) {
      const Vec2 uv(du(rng), dv(rng));
      const SurfaceDerivatives full = s->derivatives(uv), first = s->firstDerivatives(uv);
      expectSameBits(first.p, full.p, s->name() + " S");
      expectSameBits(first.su, full.su, s->name() + " Su");
      expectSameBits(first.sv, full.sv, s->name() + " Sv");
    }
  }
}

// Identities: every kind has one, equal for the same definition, different for another
// kind, another parameter, domain or name.
TEST(SurfaceReuse, IdentitiesTellSurfacesApart) {
  const auto kinds = everyKind();
  for (size_t i = 0; i < kinds.size(); ++i) {
    EXPECT_FALSE(kinds[i]->identity().empty()) << kinds[i]->name();
    EXPECT_EQ(kinds[i]->identity(), everyKind()[i]->identity()) << kinds[i]->name();
    for (size_t j = 0; j < i; ++j) EXPECT_NE(kinds[i]->identity(), kinds[j]->identity());
  }
  EXPECT_NE(SphereSurface(2.0).identity(), SphereSurface(2.0000000000000004).identity());
  EXPECT_NE(TorusSurface(3.0, 1.0).identity(), TorusSurface(3.0, 1.0, Vec3(0, 0, 1e-300)).identity());
  EXPECT_NE(BezierPatchSurface(bumpGrid(0.5)).identity(), BezierPatchSurface(bumpGrid(0.25)).identity());
  EXPECT_NE(BezierPatchSurface(bumpGrid(0.5)).identity(), BezierPatchSurface(bumpGrid(0.5), "other").identity());
  EXPECT_NE(paperP2()->identity(), paperP2(Box2{{-10, -10}, {10, 9}})->identity());
  EXPECT_NE(HeightFieldSurface("u*v", Box2{{0, 0}, {1, 1}}).identity(),
            ExpressionSurface("u", "v", "u*v", Box2{{0, 0}, {1, 1}}).identity());
}

std::string p2WithSource(double x, double chordTolerance = 0.05, double holeU = -4.0) {
  return R"({"metric": {"chordTolerance": )" + std::to_string(chordTolerance) +
         R"(, "hmin": 0.02, "hmax": 1.5, "maxAspectRatio": 6, "gradation": 2.0},
  "patches": [{"surface": {"type": "p2", "domain": [[-10, -10], [10, 10]]},
    "holes": [[{"type": "circle", "center": [)" +
         std::to_string(holeU) + R"(, 3], "radius": 1.5}]],
    "sources": [{"type": "radial", "center": [)" +
         std::to_string(x) + R"(, 0], "metric": {"alpha": 0, "h1": 0.15, "h2": 0.15}, "radius": 1.5}]}]})";
}

struct SurfaceRun {
  Mesh mesh;
  SurfaceMeshReport report;
};

SurfaceRun runReuse(const std::string& json) {
  SurfaceRun r;
  r.mesh = meshSurfaceCase(json, &r.report);
  return r;
}

void expectSameRun(const SurfaceRun& a, const SurfaceRun& b) {
  ASSERT_EQ(a.mesh.points.size(), b.mesh.points.size());
  ASSERT_EQ(a.mesh.triangles, b.mesh.triangles);
  for (size_t i = 0; i < a.mesh.points.size(); ++i) expectSameBits(a.mesh.points[i], b.mesh.points[i], "point");
  EXPECT_EQ(a.report.curvatureEvaluations, b.report.curvatureEvaluations);
  EXPECT_EQ(a.report.controlSpaceQueries, b.report.controlSpaceQueries);
  EXPECT_EQ(bitsOf(a.report.quality.chordDeviationMax), bitsOf(b.report.quality.chordDeviationMax));
  EXPECT_EQ(bitsOf(a.report.quality.qualityMean), bitsOf(b.report.quality.qualityMean));
  EXPECT_EQ(a.report.elementQuality, b.report.elementQuality);
}

// A drag: the same surface with the source moved, and back. The runs after the first
// start from the kept curvature stage; they give what a fresh build gives (the first
// run of this process at each key is one), counters included.
TEST(SurfaceReuse, RepeatedRunsWithAMovedSourceGiveTheBitsOfFreshOnes) {
  const SurfaceRun a = runReuse(p2WithSource(0.0));
  const SurfaceRun b = runReuse(p2WithSource(2.5));
  const SurfaceRun a2 = runReuse(p2WithSource(0.0));
  expectSameRun(a, a2);
  EXPECT_NE(a.mesh.triangles, b.mesh.triangles);  // the source moved the mesh
  // Another sizing is another stage: a finer chord tolerance refines the curvature stage.
  const SurfaceRun fine = runReuse(p2WithSource(0.0, 0.02));
  EXPECT_GT(fine.report.curvatureEvaluations, a.report.curvatureEvaluations);
  EXPECT_GT(fine.mesh.triangles.size(), a.mesh.triangles.size());
  expectSameRun(a, runReuse(p2WithSource(0.0)));
}

// A small sphere patch at a chord tolerance: a cheap run whose stage takes a place in the
// cache (every stage key counts against the same 4 places).
std::string smallSphere(double chordTolerance) {
  return R"({"metric": {"chordTolerance": )" + std::to_string(chordTolerance) +
         R"(, "hmin": 0.05, "hmax": 0.8, "gradation": 2.0},
  "patches": [{"surface": {"type": "sphere", "radius": 1.0, "domain": [[0.5, -0.8], [2.5, 0.8]]}}]})";
}

// The kept stage holds the contours' curvature: a moved hole is another stage. A run after
// another hole's run gives what a fresh run gives (the cache emptied of that sizing by
// runs at 5 other keys first: it keeps 4 stages, kEntries in curvature_stage_cache.cpp),
// not the other hole's stage.
TEST(SurfaceReuse, AMovedHoleIsAnotherStage) {
  const double chord = 0.045;  // a sizing no other test uses: the first run of each key is fresh
  (void)runReuse(p2WithSource(0.0, chord, -4.0));
  const SurfaceRun afterOther = runReuse(p2WithSource(0.0, chord, -1.0));
  for (double other : {0.044, 0.043, 0.042, 0.041, 0.040}) (void)runReuse(smallSphere(other));
  const SurfaceRun fresh = runReuse(p2WithSource(0.0, chord, -1.0));
  expectSameRun(afterOther, fresh);
}

}  // namespace

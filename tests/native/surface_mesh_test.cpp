// Surface meshing (paper section 3, Algorithm 1): single patches, shared contours,
// 3D quality, adaptation across patches, the JSON surface case format and its errors.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/run_case.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/surface_mesh.h"

namespace {

using namespace anisomesh;

std::string readExample(const std::string& name) {
  std::ifstream in(std::string(ANISOMESH_SOURCE_DIR) + "/examples/surface/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

using EdgeKey = std::array<int, 2>;
EdgeKey key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Conformity of a merged surface mesh: shared edges used by exactly two triangles, no
// edge used more than twice, open edges exactly the mesh's (non-shared) boundary edges,
// no element inverted in its parameter plane, no unused or duplicated vertex.
void expectConformingSurface(const Mesh& mesh, const SurfaceMeshReport& r) {
  std::map<EdgeKey, int> uses;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++uses[key(t[size_t(k)], t[size_t((k + 1) % 3)])];
  for (const auto& e : uses) EXPECT_LE(e.second, 2) << "edge used by more than two triangles";
  EXPECT_GT(r.sharedEdges, 0);
  for (const auto& e : r.sharedEdgeList) EXPECT_EQ(uses[e], 2) << "shared edge " << e[0] << "-" << e[1];
  std::set<EdgeKey> open, boundary;
  for (const auto& e : openEdges(mesh)) open.insert(e);
  for (const auto& e : mesh.edges) boundary.insert(key(e[0], e[1]));
  EXPECT_EQ(open, boundary) << "cracks: open edges differ from the non-shared contours";
  EXPECT_EQ(r.quality.inverted, 0);
  std::vector<int> used(mesh.points.size(), 0);
  for (const auto& t : mesh.triangles)
    for (int v : t) ++used[size_t(v)];
  for (size_t i = 0; i < used.size(); ++i) EXPECT_GT(used[i], 0) << "unused vertex " << i;
  // No two vertices at the same 3D place (shared curves merged, not duplicated).
  std::map<std::array<long long, 3>, int> cells;
  int duplicates = 0;
  for (const auto& p : mesh.points) {
    const std::array<long long, 3> c{std::llround(p.x() * 1e7), std::llround(p.y() * 1e7), std::llround(p.z() * 1e7)};
    if (cells[c]++ > 0) ++duplicates;
  }
  EXPECT_EQ(duplicates, 0);
  for (const auto& p : mesh.points) EXPECT_TRUE(p.allFinite());
  EXPECT_EQ(mesh.dimension, 3);
  EXPECT_EQ(mesh.params.size(), mesh.points.size());
}

void print(const char* what, const SurfaceMeshReport& r) {
  std::printf(
      "[%s] tris %d verts %d rounds %d inval %d | 3D edges in [1/sqrt2,sqrt2] %.4f  mean len %.3f  Q mean %.4f min %.3f"
      " | chord dev max %.4g (%.2f x tol) | across-shared ratio %.3f | %.2fs\n",
      what, r.triangles, r.vertices, r.rounds, r.invalidations, r.quality.edgesWithinSqrt2, r.quality.edgeLengthMean,
      r.quality.qualityMean, r.quality.qualityMin, r.quality.chordDeviationMax, r.quality.chordDeviationMaxRelative,
      r.crossSharedSizeRatioMax, r.secondsTotal);
}

TEST(SurfaceMesh, P2WithHolesQuality) {
  SurfaceMeshReport r;
  const Mesh mesh = meshSurfaceCase(readExample("surface_p2_holes.json"), &r);
  print("p2 holes", r);
  EXPECT_GT(r.triangles, 500);
  EXPECT_EQ(r.quality.inverted, 0);
  EXPECT_EQ(openEdges(mesh).size(), mesh.edges.size());
  EXPECT_GE(r.quality.edgesWithinSqrt2, 0.97);
  EXPECT_GE(r.quality.qualityMean, 0.9);
  // Default sizing sqrt(3 tol / |k|) (kDefaultChordSafety): edges and triangle interiors
  // within the tolerance. Reached: 0.80 (2.28 with the paper sizing).
  EXPECT_LE(r.quality.chordDeviationMaxRelative, 1.0);
  EXPECT_LE(r.quality.edgeChordDeviationMax, r.quality.chordDeviationMax);
}

TEST(SurfaceMesh, SphereBandClosedAcrossSeam) {
  SurfaceMeshReport r;
  const Mesh mesh = meshSurfaceCase(readExample("surface_sphere.json"), &r);
  print("sphere", r);
  expectConformingSurface(mesh, r);
  // Only the two polar circles remain open; every point lies on the unit sphere.
  for (const auto& e : mesh.edges) {
    EXPECT_NEAR(std::abs(mesh.points[size_t(e[0])].z()), std::sin(1.2), 1e-9);
    EXPECT_NEAR(std::abs(mesh.points[size_t(e[1])].z()), std::sin(1.2), 1e-9);
  }
  for (const auto& p : mesh.points) EXPECT_NEAR(p.norm(), 1.0, 1e-12);
  EXPECT_GE(r.quality.edgesWithinSqrt2, 0.97);
  EXPECT_GE(r.quality.qualityMean, 0.9);
  // Default sizing sqrt(3 tol / |k|) (kDefaultChordSafety): edges and triangle interiors
  // within the tolerance. Reached: 0.87 (2.02 with the paper sizing).
  EXPECT_LE(r.quality.chordDeviationMaxRelative, 1.0);
  EXPECT_LE(r.quality.edgeChordDeviationMax, r.quality.chordDeviationMax);
}

TEST(SurfaceMesh, ChordSafetyOneIsThePaperSizing) {
  // chordSafety = 1 (h = sqrt(8 tol / |k|): edges of metric length 1 have sagitta tol) gives
  // fewer elements, the same metric conformity, and deviations beyond the tolerance where
  // edges reach sqrt2 and triangle interiors add 4/3: the reason for the default sqrt(8/3).
  for (const char* f : {"surface_p2_holes.json", "surface_sphere.json", "surface_torus.json"}) {
    SCOPED_TRACE(f);
    SurfaceCaseSpec spec = parseSurfaceCaseJson(readExample(f));
    EXPECT_EQ(spec.options.chordSafety, kDefaultChordSafety);
    SurfaceMeshReport def, paper;
    meshSurfaceCase(spec, &def);
    spec.options.chordSafety = 1.0;
    const Mesh mesh = meshSurfaceCase(spec, &paper);
    print(f, paper);
    if (!paper.sharedEdgeList.empty()) expectConformingSurface(mesh, paper);
    EXPECT_EQ(paper.quality.inverted, 0);
    EXPECT_GE(paper.quality.edgesWithinSqrt2, 0.96);  // p2: 0.969
    EXPECT_GE(paper.quality.qualityMean, 0.9);
    EXPECT_LT(paper.triangles, def.triangles);
    EXPECT_GT(paper.quality.chordDeviationMaxRelative, 1.0);
    EXPECT_LE(def.quality.chordDeviationMaxRelative, 1.0);
  }
}

TEST(SurfaceMesh, TorusClosedWithoutBoundary) {
  SurfaceMeshReport r;
  const Mesh mesh = meshSurfaceCase(readExample("surface_torus.json"), &r);
  print("torus", r);
  expectConformingSurface(mesh, r);
  EXPECT_TRUE(mesh.edges.empty());
  // Closed surface: Euler characteristic 0.
  std::set<EdgeKey> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.insert(key(t[size_t(k)], t[size_t((k + 1) % 3)]));
  EXPECT_EQ(int(mesh.points.size()) - int(edges.size()) + int(mesh.triangles.size()), 0);
  EXPECT_GE(r.quality.edgesWithinSqrt2, 0.97);
  EXPECT_GE(r.quality.qualityMean, 0.9);
  // Default sizing sqrt(3 tol / |k|) (kDefaultChordSafety): edges and triangle interiors
  // within the tolerance. Reached: 0.82 (2.09 with the paper sizing).
  EXPECT_LE(r.quality.chordDeviationMaxRelative, 1.0);
  EXPECT_LE(r.quality.edgeChordDeviationMax, r.quality.chordDeviationMax);
  // The merged mesh goes through the Medit writer as a 3D mesh.
  const std::string text = writeMedit(mesh);
  EXPECT_NE(text.find("Dimension 3"), std::string::npos);
  const Mesh back = parseMedit(text);
  EXPECT_EQ(back.points.size(), mesh.points.size());
  EXPECT_EQ(back.triangles.size(), mesh.triangles.size());
}

TEST(SurfaceMesh, TwoPatchCConformingAndAdaptationSmoothsAcross) {
  SurfaceMeshReport with, without;
  const SurfaceCaseSpec spec = parseSurfaceCaseJson(readExample("surface_two_patch_c.json"));
  const Mesh a = meshSurfaceCase(spec, &with);
  const Mesh b = meshSurfaceCase(readExample("surface_two_patch_c_noadapt.json"), &without);
  print("two-patch C, adaptation", with);
  print("two-patch C, no adaptation", without);
  expectConformingSurface(a, with);
  expectConformingSurface(b, without);
  // Shared edges separate the two patches.
  for (const Mesh* m : {&a, &b}) {
    std::map<EdgeKey, std::set<int>> refs;
    for (size_t t = 0; t < m->triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        refs[key(m->triangles[t][size_t(k)], m->triangles[t][size_t((k + 1) % 3)])].insert(m->triangleRefs[t]);
    const auto& list = m == &a ? with.sharedEdgeList : without.sharedEdgeList;
    for (const auto& e : list) EXPECT_EQ(refs[e].size(), 2u);
  }
  EXPECT_LE(with.crossSharedSizeRatioMax, spec.options.gradation);
  EXPECT_GT(without.crossSharedSizeRatioMax, spec.options.gradation);
  EXPECT_GE(with.quality.edgesWithinSqrt2, 0.97);
  EXPECT_GE(with.quality.qualityMean, 0.9);
  EXPECT_LE(with.quality.chordDeviationMaxRelative, 1.0);
  EXPECT_LE(without.quality.chordDeviationMaxRelative, 1.0);
}

TEST(SurfaceMesh, QuadsOnSurfacesConformAcrossSharedContours) {
  // Quad-dominant and all-quad meshes of a two-patch case and of the sphere band (seam
  // shared with itself): quads present, none inverted in (u, v), every shared edge used
  // by exactly two elements, open edges exactly the non-shared contours.
  for (const char* f : {"surface_two_patch_c.json", "surface_sphere.json"})
    for (int mode = 0; mode < 2; ++mode) {
      SCOPED_TRACE(std::string(f) + (mode ? " allQuads" : " quads"));
      SurfaceCaseSpec spec = parseSurfaceCaseJson(readExample(f));
      (mode ? spec.options.allQuads : spec.options.quads) = true;
      SurfaceMeshReport r;
      const Mesh mesh = meshSurfaceCase(spec, &r);
      print(f, r);
      EXPECT_GT(mesh.quads.size(), mode ? 1000u : 300u);
      if (mode) {
        EXPECT_TRUE(mesh.triangles.empty());
      }
      EXPECT_EQ(mesh.quadRefs.size(), mesh.quads.size());
      EXPECT_EQ(r.quality.inverted, 0);
      EXPECT_EQ(r.elementQuality.size(), mesh.triangles.size() + mesh.quads.size());
      std::map<EdgeKey, int> uses;
      for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) ++uses[key(t[size_t(k)], t[size_t((k + 1) % 3)])];
      for (const auto& q : mesh.quads)
        for (int k = 0; k < 4; ++k) ++uses[key(q[size_t(k)], q[size_t((k + 1) % 4)])];
      for (const auto& e : uses) EXPECT_LE(e.second, 2);
      EXPECT_GT(r.sharedEdges, 0);
      for (const auto& e : r.sharedEdgeList) EXPECT_EQ(uses[e], 2) << "shared edge " << e[0] << "-" << e[1];
      std::set<EdgeKey> open, boundary;
      for (const auto& e : uses)
        if (e.second == 1) open.insert(e.first);
      for (const auto& e : mesh.edges) boundary.insert(key(e[0], e[1]));
      EXPECT_EQ(open, boundary);
      // Shared curve points lie on both patches: all-quad midpoints of a shared edge are one vertex.
      std::vector<int> used(mesh.points.size(), 0);
      for (const auto& q : mesh.quads)
        for (int v : q) ++used[size_t(v)];
      for (const auto& t : mesh.triangles)
        for (int v : t) ++used[size_t(v)];
      for (size_t i = 0; i < used.size(); ++i) EXPECT_GT(used[i], 0) << "unused vertex " << i;
      EXPECT_GE(r.quality.qualityMean, 0.8);
      EXPECT_LE(r.quality.chordDeviationMaxRelative, 1.0);  // merges leaving the tolerance are undone
      // 3D quads of the sphere stay on it (corners on the unit sphere).
      if (std::string(f) == "surface_sphere.json") {
        for (const auto& p : mesh.points) EXPECT_NEAR(p.norm(), 1.0, 1e-12);
      }
    }
}

TEST(SurfaceMesh, TwoFlatPatchesShareIdenticalVertices) {
  // Two planes with different parameterizations (B is scaled and reversed in u).
  SurfaceModel m;
  SurfacePatch a, b;
  a.surface = std::make_shared<PlaneSurface>(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  b.surface = std::make_shared<PlaneSurface>(Vec3(2, 0, 0), Vec3(-0.5, 0, 0), Vec3(0, 1, 0), Box2{{0, 0}, {2, 1}});
  a.name = "A", b.name = "B", a.id = 1, b.id = 2;
  auto rect = [](const Box2& bx) {
    Contour c;
    const Vec2 p0 = bx.lo, p1(bx.hi.x(), bx.lo.y()), p2 = bx.hi, p3(bx.lo.x(), bx.hi.y());
    c.add(std::make_shared<LineCurve>(p0, p1));
    c.add(std::make_shared<LineCurve>(p1, p2));
    c.add(std::make_shared<LineCurve>(p2, p3));
    c.add(std::make_shared<LineCurve>(p3, p0));
    return c;
  };
  a.domain.outer = rect({{0, 0}, {1, 1}});
  b.domain.outer = rect({{0, 0}, {2, 1}});
  m.patches = {a, b};
  // A's right edge (x = 1, going up) is B's right edge in u = 2 (x = 1, going up): same direction.
  m.shared.push_back({{0, 0, 1}, {1, 0, 1}, false});
  SurfaceMeshOptions o;
  o.metric.hmax = 0.15;
  SurfaceMeshReport r;
  const Mesh mesh = meshSurfaceModel(m, o, &r);
  expectConformingSurface(mesh, r);
  EXPECT_EQ(r.sharedEdges, int(std::round(1.0 / 0.15)));
  // B's parameterization is mirrored: it was flipped so both sides agree in 3D
  // (every shared edge traversed once each way).
  std::map<EdgeKey, int> dir;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int x = t[size_t(k)], y = t[size_t((k + 1) % 3)];
      dir[key(x, y)] += x < y ? 1 : -1;
    }
  for (const auto& e : r.sharedEdgeList) EXPECT_EQ(dir[e], 0);
  for (const auto& t : mesh.triangles) {
    const Vec3 n = (mesh.points[size_t(t[1])] - mesh.points[size_t(t[0])])
                       .cross(mesh.points[size_t(t[2])] - mesh.points[size_t(t[0])]);
    EXPECT_GT(n.z(), 0.0);
  }
  for (const auto& e : r.sharedEdgeList) {
    EXPECT_NEAR(mesh.points[size_t(e[0])].x(), 1.0, 1e-12);
    EXPECT_NEAR(mesh.points[size_t(e[1])].x(), 1.0, 1e-12);
  }
}

TEST(SurfaceMesh, Metric3DFromParameterKeepsLengths) {
  const auto s = paperP2();
  const Vec2 uv(0.7, -1.3);
  const SurfaceDerivatives d = s->derivatives(uv);
  const Metric m = Metric::fromSizes(0.4, 0.05, 0.3);
  const Mat3 t = metric3DFromParameter(m, d);
  for (const Vec2& du : {Vec2(1, 0), Vec2(0, 1), Vec2(0.3, -0.8)}) {
    const Vec3 x = d.jacobian() * du;
    EXPECT_NEAR(std::sqrt(x.dot(t * x)), m.length(du), 1e-9 * m.length(du));
  }
  // Pulling the 3D metric back gives the metric again.
  EXPECT_LT(difference(pullBackMetric(t, d), m), 1e-9);
  // Along the normal: the finest tangent size (the largest eigenvalue of the tangent part,
  // found here by the iterative 3x3 solver the closed form replaced), so the two largest
  // eigenvalues of t are equal and the normal is an eigenvector of theirs.
  const Vec3 n = d.su.cross(d.sv).normalized();
  const Vec3 ev = Eigen::SelfAdjointEigenSolver<Mat3>(t).eigenvalues();
  const Mat3 p = Mat3::Identity() - n * n.transpose();
  const double tangentMax = Eigen::SelfAdjointEigenSolver<Mat3>(p * t * p).eigenvalues().maxCoeff();
  EXPECT_NEAR(n.dot(t * n), tangentMax, 1e-12 * tangentMax);
  EXPECT_NEAR(ev(1), ev(2), 1e-12 * ev(2));
  EXPECT_LT((t * n - tangentMax * n).norm(), 1e-12 * tangentMax);
}

TEST(SurfaceMesh, PatchControlSpaceFollowsCurvature) {
  SurfacePatch p;
  p.surface = std::make_shared<SphereSurface>(1.0);
  p.domain.outer.add(std::make_shared<LineCurve>(Vec2(0, -1), Vec2(1, -1)));
  SurfaceMeshOptions o;
  o.metric.chordTolerance = 0.005;
  o.gradation = 0.0;
  const auto cs = buildPatchControlSpace(p, {}, o);
  SurfaceMetricOptions sized = o.metric;  // the tolerance the sizes come from
  sized.chordTolerance /= o.chordSafety * o.chordSafety;
  for (const Vec2& uv : {Vec2(1.0, 0.3), Vec2(4.0, -0.9), Vec2(2.5, 1.1)}) {
    const Metric want = parameterMetric(*p.surface, uv, sized);
    EXPECT_LT(difference(cs->metricAt(uv), want), 0.3) << uv.transpose();
  }
}

TEST(SurfaceMesh, ContourCurvatureEntersTheInitialControlSpace) {
  // A flat patch (no surface curvature) with a circular hole of radius r: before any
  // discretization, the control space along the hole asks for the contour's chord size
  // sqrt(8 tol' r) (tol' = tol / chordSafety^2) along its tangent; without the contour
  // source it is hmax there.
  const double r = 0.2, tol = 1e-3;
  SurfacePatch p;
  p.surface = std::make_shared<PlaneSurface>(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Box2{{0, 0}, {1, 1}});
  p.domain.outer.add(std::make_shared<LineCurve>(Vec2(0, 0), Vec2(1, 0)));
  p.domain.outer.add(std::make_shared<LineCurve>(Vec2(1, 0), Vec2(1, 1)));
  p.domain.outer.add(std::make_shared<LineCurve>(Vec2(1, 1), Vec2(0, 1)));
  p.domain.outer.add(std::make_shared<LineCurve>(Vec2(0, 1), Vec2(0, 0)));
  Contour hole;
  hole.add(std::make_shared<ArcCurve>(Vec2(0.5, 0.5), r, 0.0, 6.283185307179586));
  p.domain.holes.push_back(hole);
  SurfaceMeshOptions o;
  o.metric.chordTolerance = tol;
  o.metric.hmax = 0.2;
  o.gradation = 0.0;
  const double want = std::sqrt(8.0 * tol / (o.chordSafety * o.chordSafety) * r);
  const auto cs = buildPatchControlSpace(p, {}, o);
  for (double a : {0.3, 1.9, 4.0}) {
    const Vec2 x(0.5 + r * std::cos(a), 0.5 + r * std::sin(a)), tangent(-std::sin(a), std::cos(a));
    EXPECT_NEAR(cs->metricAt(x).sizeAlong(tangent), want, 0.15 * want) << a;
  }
  o.contourCurvature = false;
  const auto plain = buildPatchControlSpace(p, {}, o);
  EXPECT_NEAR(plain->metricAt(Vec2(0.5 + r, 0.5)).sizeAlong(Vec2(0, 1)), 0.2, 1e-9);
  // Meshed: the first discretization already follows the hole (no section 3.2 invalidation),
  // where without the source the chord check has to invalidate the hole.
  SurfaceMeshReport with, without;
  o.contourCurvature = true;
  meshSurfacePatch(p, o, &with);
  o.contourCurvature = false;
  meshSurfacePatch(p, o, &without);
  EXPECT_EQ(with.invalidations, 0);
  EXPECT_GT(without.invalidations, 0);
  EXPECT_LE(with.quality.chordDeviationMaxRelative, 1.0);
}

TEST(SurfaceMesh, ContourCurvatureAvoidsInvalidationsOnP2AndSphere) {
  for (const char* f : {"surface_p2_holes.json", "surface_sphere.json"}) {
    SCOPED_TRACE(f);
    SurfaceCaseSpec spec = parseSurfaceCaseJson(readExample(f));
    SurfaceMeshReport with, without;
    meshSurfaceCase(spec, &with);
    spec.options.contourCurvature = false;
    meshSurfaceCase(spec, &without);
    EXPECT_EQ(with.invalidations, 0);
    EXPECT_GT(without.invalidations, 0);
  }
}

TEST(SurfaceMesh, Source3DRefinesAroundItsCenter) {
  SurfaceCaseSpec spec = parseSurfaceCaseJson(readExample("surface_sphere.json"));
  spec.model.sources3d.push_back({Vec3(1, 0, 0.3), 0.025, 0.15});
  SurfaceMeshReport r;
  const Mesh mesh = meshSurfaceCase(spec, &r);
  expectConformingSurface(mesh, r);
  // Edges inside the source's ball are about h; far away they follow the curvature (~0.11;
  // ~0.066 along the polar circles, whose 3D curvature is 1 / cos 1.2).
  double nearMax = 0, farMin = 1e9;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = mesh.points[size_t(t[size_t(k)])];
      const Vec3& b = mesh.points[size_t(t[size_t((k + 1) % 3)])];
      const double d = (0.5 * (a + b) - Vec3(1, 0, 0.3)).norm(), l = (a - b).norm();
      if (d < 0.08) nearMax = std::max(nearMax, l);
      if (d > 0.8) farMin = std::min(farMin, l);
    }
  EXPECT_LT(nearMax, 0.025 * 1.6);
  EXPECT_GT(farMin, 0.025 * 1.6);
}

TEST(SurfaceMesh, EverySurfaceExampleParses) {
  for (const char* f : {"surface_p2_holes.json", "surface_sphere.json", "surface_torus.json",
                        "surface_two_patch_c.json", "surface_two_patch_c_noadapt.json"}) {
    SCOPED_TRACE(f);
    const std::string text = readExample(f);
    EXPECT_TRUE(isSurfaceCaseJson(text));
    EXPECT_NO_THROW(parseSurfaceCaseJson(text));
  }
  EXPECT_FALSE(isSurfaceCaseJson(R"({"domain": {}, "controlSpace": {}})"));
}

// --- errors ---------------------------------------------------------------------------

void expectSurfaceError(const std::string& json, ErrorCode code, const std::vector<std::string>& substrings) {
  try {
    meshSurfaceCase(json);
    FAIL() << "no error for " << json;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    for (const auto& s : substrings) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
  }
}

const char* kMetric = R"("metric": {"chordTolerance": 0.05, "hmax": 0.3, "hmin": 0.01})";

TEST(SurfaceMeshErrors, ParseErrorsNameThePath) {
  expectSurfaceError(R"({"patches": [{"surface": {"type": "sphere"}}]})", ErrorCode::ParseError,
                     {"patches[0].surface.radius", "missing"});
  expectSurfaceError(R"({"patches": [{"surface": {"type": "plane", "colour": 1}}]})", ErrorCode::ParseError,
                     {"patches[0].surface.colour", "unknown field"});
  expectSurfaceError(R"({"patches": [{"surface": {"type": "cone"}}]})", ErrorCode::ParseError,
                     {"patches[0].surface.type", "unknown surface type"});
  expectSurfaceError(R"({"patches": [{"surface": {"type": "plane"}, "outer": [{"type": "line", "p1": [0, 0]}]}]})",
                     ErrorCode::ParseError, {"patches[0].outer[0].p2", "missing"});
  expectSurfaceError(
      R"({"patches": [{"surface": {"type": "plane"}}], "shared": [{"a": {"patch": "X", "curve": 0}, "b": {"patch": 0, "curve": 1}}]})",
      ErrorCode::ParseError, {"shared[0].a.patch", "no patch named 'X'"});
  expectSurfaceError(R"({"patches": [{"surface": {"type": "plane"}}], "adaptation": "yes"})", ErrorCode::ParseError,
                     {"adaptation", "expected true or false"});
  expectSurfaceError("{\"patches\": [", ErrorCode::ParseError, {"malformed JSON"});
}

// Out-of-range options are refused, not clamped or taken as "off" (a negative chord
// tolerance behaved as 0, negative improvement passes changed the mesh).
TEST(SurfaceMeshErrors, OutOfRangeOptionsAreRefused) {
  const std::string plane = R"("patches": [{"surface": {"type": "plane"}}])";
  expectSurfaceError("{" + plane + R"(, "metric": {"chordTolerance": -1, "hmax": 0.3, "hmin": 0.01}})",
                     ErrorCode::InvalidArgument, {"metric", "chordTolerance and angleTolerance", ">= 0"});
  expectSurfaceError("{" + plane + R"(, "metric": {"angleTolerance": -0.1, "hmax": 0.3, "hmin": 0.01}})",
                     ErrorCode::InvalidArgument, {"metric", ">= 0"});
  expectSurfaceError("{" + plane + ", " + kMetric + R"(, "options": {"improvementPasses": -1}})",
                     ErrorCode::InvalidArgument, {"options.improvementPasses", ">= 0"});
  expectSurfaceError("{" + plane + ", " + kMetric + R"(, "options": {"maxRounds": 0}})", ErrorCode::InvalidArgument,
                     {"options.maxRounds", ">= 1"});
  // The limits themselves are valid.
  EXPECT_NO_THROW(meshSurfaceCase(
      "{" + plane +
      R"(, "metric": {"chordTolerance": 0, "angleTolerance": 0, "hmax": 0.3, "hmin": 0.01}, "options": {"improvementPasses": 0, "maxRounds": 1}})"));
}

// A parameterization that folds inside the patch (x = u^2 over [-1, 1] covers x in [0, 1]
// twice: Su x Sv = 0 along u = 0, the normal turns over) is refused; a kink (|u|), a fast
// oscillation and a thin tube turn the normal between samples without vanishing and mesh.
TEST(SurfaceMeshErrors, AFoldingParameterizationIsRefused) {
  auto expressionCase = [](const std::string& x, const std::string& y, const std::string& z,
                           const std::string& domain) {
    return R"({"metric": {"chordTolerance": 0.02, "hmin": 0.02, "hmax": 0.5}, "patches": [{"name": "p", "surface": {"type": "expression", "x": ")" +
           x + R"(", "y": ")" + y + R"(", "z": ")" + z + R"(", "domain": )" + domain + "}}]}";
  };
  expectSurfaceError(expressionCase("u*u", "v", "0", "[[-1, 0], [1, 1]]"), ErrorCode::InvalidSurface,
                     {"patch 'p'", "folds over itself"});
  for (const char* z : {"10*abs(u)", "0.2*sin(40*u)"})
    EXPECT_NO_THROW(meshSurfaceCase(expressionCase("u", "v", z, "[[-1, 0], [1, 1]]"))) << z;
  EXPECT_NO_THROW(meshSurfaceCase(
      expressionCase("(1+0.05*cos(v))*cos(u)", "(1+0.05*cos(v))*sin(u)", "0.05*sin(v)", "[[0, 0], [3, 6.2]]")));
}

TEST(SurfaceMeshErrors, BadExpressionNamesTheColumn) {
  expectSurfaceError(
      R"J({"patches": [{"surface": {"type": "expression", "x": "u", "y": "v", "z": "sin(u +* v)", "domain": [[0,0],[1,1]]}}]})J",
      ErrorCode::ParseError, {"patches[0].surface.z", "z(u,v)", "column"});
}

TEST(SurfaceMeshErrors, NaNSurfaceNamesPatchAndPlace) {
  expectSurfaceError(
      std::string(R"({)") + kMetric +
          R"J(, "patches": [{"name": "bad", "surface": {"type": "expression", "x": "u", "y": "v", "z": "sqrt(u - 0.5)", "domain": [[0,0],[1,1]]}}]})J",
      ErrorCode::InvalidSurface, {"patch 'bad'", "(u, v) = ("});
}

TEST(SurfaceMeshErrors, DegenerateParameterizationNamesPatchAndPlace) {
  expectSurfaceError(
      std::string(R"({)") + kMetric +
          R"(, "patches": [{"name": "flat", "surface": {"type": "expression", "x": "u+v", "y": "u+v", "z": "u+v", "domain": [[0,0],[1,1]]}}]})",
      ErrorCode::InvalidSurface, {"patch 'flat'", "degenerate", "(u, v) = ("});
}

TEST(SurfaceMeshErrors, ContourOffTheDomainNamesPatch) {
  expectSurfaceError(std::string(R"({)") + kMetric + R"(, "patches": [{"name": "P", "surface": {"type": "plane"},
      "outer": [{"type": "polyline", "points": [[0, 0], [1.5, 0], [1.5, 1], [0, 1], [0, 0]]}]}]})",
                     ErrorCode::InvalidDomain, {"patch 'P'", "outer", "parameter domain", "(u, v) = (1."});
}

TEST(SurfaceMeshErrors, SharedCurvesThatDoNotMatchNameBothPatches) {
  expectSurfaceError(std::string(R"({)") + kMetric + R"(, "patches": [
      {"name": "A", "surface": {"type": "plane"}},
      {"name": "B", "surface": {"type": "plane", "origin": [1.2, 0, 0]}}],
      "shared": [{"a": {"patch": "A", "curve": 1}, "b": {"patch": "B", "curve": 3}}]})",
                     ErrorCode::InvalidSurface, {"patch 'A'", "patch 'B'", "shared curve mismatch"});
}

}  // namespace

// Per-patch parameters of a merged surface mesh (patch_params.h): every element corner's
// (u, v) in its own patch maps to the corner's 3D point, also on shared curves, where the
// merged mesh's single (u, v) per vertex belongs to the other patch.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "anisomesh/io/case_json.h"
#include "anisomesh/pipeline/pipeline.h"
#include "anisomesh/surface/patch_params.h"

namespace {

using namespace anisomesh;

std::string readSurfaceExample(const std::string& name) {
  std::ifstream in(std::string(ANISOMESH_SOURCE_DIR) + "/examples/surface/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Corner c of element e: its vertex.
int cornerVertex(const Mesh& mesh, size_t e, int k) {
  return e < mesh.triangles.size() ? mesh.triangles[e][size_t(k)] : mesh.quads[e - mesh.triangles.size()][size_t(k)];
}

void expectCornersOnSurface(const std::string& file, bool expectShared) {
  const SurfaceCaseSpec spec = parseSurfaceCaseJson(readSurfaceExample(file));
  const Mesh mesh = meshSurfaceCase(spec);
  const std::vector<int> patch = elementPatches(spec.model, mesh);
  const std::vector<Vec2> corners = patchCornerParams(spec.model, mesh);
  ASSERT_EQ(patch.size(), mesh.triangles.size() + mesh.quads.size());
  ASSERT_EQ(corners.size(), 3 * mesh.triangles.size() + 4 * mesh.quads.size());
  size_t c = 0, moved = 0;
  double worst = 0.0;
  for (size_t e = 0; e < patch.size(); ++e) {
    ASSERT_GE(patch[e], 0) << file << " element " << e;
    const Surface& s = *spec.model.patches[size_t(patch[e])].surface;
    const int n = e < mesh.triangles.size() ? 3 : 4;
    for (int k = 0; k < n; ++k, ++c) {
      const int v = cornerVertex(mesh, e, k);
      EXPECT_TRUE(s.domain().contains(corners[c])) << file << " corner " << c;
      const double dd = (s.point(corners[c]) - mesh.points[size_t(v)]).norm();
      worst = std::max(worst, dd);
      if ((corners[c] - mesh.params[size_t(v)]).norm() > 1e-9) ++moved;
    }
  }
  EXPECT_LT(worst, 1e-7) << file << ": a corner's (u, v) does not map to its vertex";
  if (expectShared)
    EXPECT_GT(moved, 0u) << file << ": no corner had another patch's parameters";
  else
    EXPECT_EQ(moved, 0u) << file;
}

TEST(SurfacePatchParams, TwoPatchCornersMapToTheirVertices) {
  expectCornersOnSurface("surface_two_patch_c.json", true);
}

// A patch shared with itself along a seam (sphere band: u = 0 / 2 pi; torus: both
// directions): an element across the seam has its seam corners on its own side, so no
// element spans more than half the domain, and every corner still maps to its vertex.
void expectSeamElementsCompact(const std::string& file, size_t minAcross) {
  const SurfaceCaseSpec spec = parseSurfaceCaseJson(readSurfaceExample(file));
  const Mesh mesh = meshSurfaceCase(spec);
  const std::vector<Vec2> corners = patchCornerParams(spec.model, mesh);
  const Surface& s = *spec.model.patches[0].surface;
  const Vec2 size = s.domain().hi - s.domain().lo;
  size_t c = 0, across = 0, wide = 0;
  double worst = 0.0;
  for (size_t e = 0; e < mesh.triangles.size() + mesh.quads.size(); ++e) {
    const int n = e < mesh.triangles.size() ? 3 : 4;
    Vec2 lo = corners[c], hi = corners[c], vlo = mesh.params[size_t(cornerVertex(mesh, e, 0))], vhi = vlo;
    for (int k = 0; k < n; ++k, ++c) {
      const Vec2 vp = mesh.params[size_t(cornerVertex(mesh, e, k))];
      lo = lo.cwiseMin(corners[c]), hi = hi.cwiseMax(corners[c]);
      vlo = vlo.cwiseMin(vp), vhi = vhi.cwiseMax(vp);
      worst = std::max(worst, (s.point(corners[c]) - mesh.points[size_t(cornerVertex(mesh, e, k))]).norm());
    }
    if ((vhi - vlo).x() > 0.5 * size.x() || (vhi - vlo).y() > 0.5 * size.y()) ++across;
    if ((hi - lo).x() > 0.5 * size.x() || (hi - lo).y() > 0.5 * size.y()) ++wide;
  }
  EXPECT_GE(across, minAcross) << file << ": elements whose vertex parameters span the seam";
  EXPECT_EQ(wide, 0u) << file << ": elements whose corners still span the domain";
  EXPECT_LT(worst, 1e-7) << file << ": a corner's (u, v) does not map to its vertex";
}

TEST(SurfacePatchParams, ElementsAcrossASeamKeepTheirCornersOnTheirSide) {
  expectSeamElementsCompact("surface_sphere.json", 10);
  expectSeamElementsCompact("surface_torus.json", 10);
}

TEST(SurfacePatchParams, SinglePatchKeepsTheVertexParameters) {
  expectCornersOnSurface("surface_p2_holes.json", false);
}

}  // namespace

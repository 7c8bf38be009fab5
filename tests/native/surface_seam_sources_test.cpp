// A source next to a periodic seam acts on both of its sides: the sphere band's u = 0 and
// u = 2 pi are one curve, so a radial source at u = 0.05 refines the mesh around it in 3D
// as evenly as the same source away from the seam does.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "anisomesh/io/case_json.h"
#include "anisomesh/pipeline/pipeline.h"

namespace {

using namespace anisomesh;

std::string sphereWithSource(double u) {
  std::ifstream in(std::string(ANISOMESH_SOURCE_DIR) + "/examples/surface/surface_sphere.json");
  std::stringstream ss;
  ss << in.rdbuf();
  nlohmann::json c = nlohmann::json::parse(ss.str());
  c["patches"][0]["sources"] = nlohmann::json::array({{{"type", "radial"},
                                                       {"center", {u, 0.0}},
                                                       {"metric", {{"alpha", 0.0}, {"h1", 0.04}, {"h2", 0.04}}},
                                                       {"radius", 0.5}}});
  return c.dump();
}

// Vertices within 0.4 of the source's 3D point, on each side of the meridian plane through it.
std::pair<int, int> verticesAround(double u) {
  const Mesh mesh = meshSurfaceCase(parseSurfaceCaseJson(sphereWithSource(u)));
  const Vec3 centre(std::cos(u), std::sin(u), 0.0), side(-std::sin(u), std::cos(u), 0.0);
  int before = 0, after = 0;
  for (const Vec3& p : mesh.points)
    if ((p - centre).norm() < 0.4) ++((p - centre).dot(side) < 0.0 ? before : after);
  return {before, after};
}

TEST(SurfaceSeamSources, ASourceAtTheSeamRefinesBothSides) {
  const auto [farBefore, farAfter] = verticesAround(M_PI);
  const auto [before, after] = verticesAround(0.05);
  ASSERT_GT(farBefore, 100);
  ASSERT_GT(farAfter, 100);
  // Away from the seam both sides are alike; at the seam they must be too (without the
  // source's image across the seam: 134 against 331).
  EXPECT_GT(std::min(before, after), 0.8 * std::max(before, after)) << before << " / " << after;
  EXPECT_GT(before + after, 0.8 * (farBefore + farAfter)) << before + after << " vs " << farBefore + farAfter;
}

}  // namespace

#include <gtest/gtest.h>

#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/svg.h"

using namespace anisomesh;

namespace {

Mesh twoTriangles() {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  return m;
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(Svg, OnePolygonPerElementAndOneLinePerBoundaryEdge) {
  const std::string svg = writeSvg(twoTriangles(), {});
  EXPECT_EQ(count(svg, "<polygon"), 2u);
  EXPECT_EQ(count(svg, "<line"), 4u);
  // Aspect ratio kept: 2 x 1 domain in an 800 wide picture.
  EXPECT_NE(svg.find("height=\"410\""), std::string::npos) << svg.substr(0, 200);
}

TEST(Svg, ColoursElementsByValueAndChecksTheCount) {
  SvgOptions o;
  o.elementValues = {0.0, 1.0};
  const std::string svg = writeSvg(twoTriangles(), o);
  EXPECT_NE(svg.find("#ff0040"), std::string::npos);  // value 0: red
  EXPECT_NE(svg.find("#00c840"), std::string::npos);  // value 1: green
  o.elementValues = {0.5};
  EXPECT_THROW(writeSvg(twoTriangles(), o), Error);
}

TEST(Svg, View3DPaintsFarthestFirstAndDrawsTheOverlay) {
  // Two parallel triangles, the upper one (z = 1) nearer to a viewer above: drawn last.
  Mesh m;
  m.dimension = 3;
  m.points = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  SvgOptions o;
  o.view3d = true;
  o.elevation = 1.2;
  o.elementValues = {0.0, 1.0};  // near one red, far one green
  o.overlay = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}};
  const std::string svg = writeSvg(m, o);
  EXPECT_EQ(count(svg, "<polygon"), 3u);
  const size_t green = svg.find("fill=\"#00"), red = svg.find("fill=\"#");
  ASSERT_NE(green, std::string::npos);
  EXPECT_EQ(red, green) << "the far (green) triangle comes first";
  EXPECT_NE(svg.find("fill=\"none\""), std::string::npos);
}

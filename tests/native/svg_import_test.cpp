// Planar domains from SVG (io/svg_import.h): path commands, shapes, nesting into holes,
// scaling, and the errors of drawings that are no domain.
#include <gtest/gtest.h>

#include <cmath>

#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"
#include "anisomesh/io/svg_import.h"
#include "anisomesh/pipeline/pipeline.h"

namespace {

using namespace anisomesh;

// Meshes a domain with a uniform size and returns the summed triangle area.
double meshedArea(const nlohmann::json& domain, double h = 0.05) {
  nlohmann::json c = {{"domain", domain}, {"controlSpace", {{"hmin", h}, {"hmax", h}}}};
  const Mesh mesh = meshCase(parseCaseJson(c.dump()));
  EXPECT_GT(mesh.triangles.size(), 50u);
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.points[size_t(t[0])], b = mesh.points[size_t(t[1])], d = mesh.points[size_t(t[2])];
    area += 0.5 * ((b - a).x() * (d - a).y() - (b - a).y() * (d - a).x());
  }
  return area;
}

TEST(SvgImport, SquareWithCircularHoleMeshes) {
  const std::string svg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 200">
    <path d="M10,10 H210 V210 H10 Z" fill="none"/>
    <circle cx="110" cy="110" r="50"/>
  </svg>)";
  SvgImportOptions o;
  o.size = 2.0;
  const nlohmann::json d = domainJsonFromSvg(svg, o);
  ASSERT_EQ(d["holes"].size(), 1u);
  EXPECT_EQ(d["outer"].size(), 4u);
  EXPECT_EQ(d["holes"][0].size(), 4u);  // two half circles, 90-degree cubic pieces
  // Square of side 2 minus a circle of radius 0.5 (cubic arcs: within 1e-3 of the area).
  EXPECT_NEAR(meshedArea(d), 4.0 - M_PI * 0.25, 4e-3);
}

TEST(SvgImport, EveryPathCommandAbsoluteAndRelative) {
  // A rounded shape: lines (L, l, H, h, V, v), a cubic with its smooth continuation (C, s),
  // a quadratic with its smooth continuation (Q, t), an arc (a); y flipped, scaled to 1.
  const std::string svg = R"(<svg><path d="M0 0 L40 0 l10 0 h10 H70 v10 V20 C70 30 60 40 50 40 s-20 0 -20 -10
      Q30 30 20 30 t-10 -10 a5 5 0 0 1 -10 -10 z"/></svg>)";
  const nlohmann::json d = domainJsonFromSvg(svg);
  EXPECT_TRUE(d["holes"].empty());
  int lines = 0, beziers = 0;
  double xmax = 0, ymax = 0;
  for (const auto& c : d["outer"]) {
    (c["type"] == "line" ? lines : beziers)++;
    for (const auto& p : c.contains("points") ? c["points"] : nlohmann::json::array({c["p1"], c["p2"]})) {
      xmax = std::max(xmax, p[0].get<double>());
      ymax = std::max(ymax, p[1].get<double>());
    }
  }
  EXPECT_EQ(lines, 7);  // six drawn, one closing (z)
  EXPECT_GE(beziers, 5);
  EXPECT_NEAR(std::max(xmax, ymax), 1.0, 1e-9);
  EXPECT_GT(meshedArea(d, 0.05), 0.2);
}

TEST(SvgImport, NestedShapesAndPolygonAndRect) {
  // rect outer, polygon hole and an ellipse hole; the y flip keeps the picture upright.
  const std::string svg = R"(<svg><rect x="0" y="0" width="100" height="50"/>
    <polygon points="10,10 30,10 20,40"/><ellipse cx="70" cy="25" rx="15" ry="10"/></svg>)";
  const nlohmann::json d = domainJsonFromSvg(svg);
  ASSERT_EQ(d["holes"].size(), 2u);
  // Polygon hole: apex at SVG y = 40 (down) is at y = (50 - 40) / 100 after the flip.
  bool apex = false;
  for (const auto& c : d["holes"][0])
    for (const auto& p : {c["p1"], c["p2"]})
      apex = apex || (std::abs(p[0].get<double>() - 0.2) < 1e-12 && std::abs(p[1].get<double>() - 0.1) < 1e-12);
  EXPECT_TRUE(apex);
  EXPECT_NEAR(meshedArea(d, 0.02), 0.5 - 0.5 * 0.2 * 0.3 - M_PI * 0.15 * 0.1, 2e-3);
}

TEST(SvgImport, DrawingsThatAreNoDomain) {
  auto code = [](const std::string& svg) {
    try {
      domainJsonFromSvg(svg);
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Internal;
  };
  EXPECT_EQ(code(R"(<svg><path d="M0 0 L10 0 L10 10"/></svg>)"), ErrorCode::OpenContour);
  EXPECT_EQ(code(R"(<svg><rect width="1" height="1"/><rect x="5" width="1" height="1"/></svg>)"),
            ErrorCode::InvalidDomain);
  EXPECT_EQ(code(R"(<svg><rect width="10" height="10"/><rect x="1" y="1" width="8" height="8"/>
      <rect x="2" y="2" width="2" height="2"/></svg>)"),
            ErrorCode::InvalidDomain);
  EXPECT_EQ(code(R"(<svg><path d="M0 0 L1e 0 Z"/></svg>)"), ErrorCode::ParseError);
  EXPECT_EQ(code(R"(<svg><path d="M0 0 X10 0 Z"/></svg>)"), ErrorCode::ParseError);
  EXPECT_EQ(code("<svg></svg>"), ErrorCode::InvalidDomain);
}

}  // namespace

namespace {

// Domain area of an SVG drawing (size 1 along its larger side, no flip needed for areas).
double svgArea(const std::string& svg) { return meshedArea(domainJsonFromSvg(svg), 0.02); }

TEST(SvgImport, TransformsOfShapesAndGroupsApply) {
  // A 100 x 50 rectangle rotated by 90 degrees about its centre is 50 x 100: after scaling
  // its larger side to 1, a 0.5 x 1 domain (unrotated it was 1 x 0.5: the same area, so the
  // shape is checked through its box).
  const nlohmann::json r =
      domainJsonFromSvg(R"svg(<svg><rect width="100" height="50" transform="rotate(90 50 25)"/></svg>)svg");
  double xmax = 0, ymax = 0;
  for (const auto& c : r["outer"])
    for (const auto& p : {c["p1"], c["p2"]})
      xmax = std::max(xmax, p[0].get<double>()), ymax = std::max(ymax, p[1].get<double>());
  EXPECT_NEAR(xmax, 0.5, 1e-12);
  EXPECT_NEAR(ymax, 1.0, 1e-12);
  // A hole drawn at twice its size inside a group scaled by 0.5 (and translated): a hole of
  // radius 10 in a 100 x 100 square, not "2 outermost shapes".
  const std::string grouped = R"svg(<svg><rect width="100" height="100"/>
      <g transform="translate(50 50) scale(0.5)"><circle cx="0" cy="0" r="20"/></g>
      <g transform="matrix(1 0 0 1 10 10)"><g transform="skewX(0)"><rect x="5" y="5" width="10" height="10"/></g></g></svg>)svg";
  const nlohmann::json g = domainJsonFromSvg(grouped);
  EXPECT_EQ(g["holes"].size(), 2u);
  EXPECT_NEAR(svgArea(grouped), 1.0 - M_PI * 0.01 - 0.01, 2e-3);
  // Rounded corners: rx = 10 on a 100 x 100 square removes (4 - pi) rx^2.
  EXPECT_NEAR(svgArea(R"svg(<svg><rect width="100" height="100" rx="10"/></svg>)svg"), 1.0 - (4.0 - M_PI) * 0.01, 2e-3);
  // A transform that is not one: a parse error naming it.
  try {
    domainJsonFromSvg(R"svg(<svg><rect width="1" height="1" transform="scale(0)"/></svg>)svg");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ParseError);
    EXPECT_NE(std::string(e.what()).find("not an invertible map"), std::string::npos) << e.what();
  }
  try {
    domainJsonFromSvg(R"svg(<svg><rect width="1" height="1" transform="wobble(3)"/></svg>)svg");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown function 'wobble'"), std::string::npos) << e.what();
  }
}

}  // namespace

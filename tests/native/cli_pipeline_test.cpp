// CLI runs of the planar pipeline: bad input is reported (named, exit 1, no output
// file), --stats carries the pipeline report, .svg output.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_test_util.h"

using namespace clitest;

namespace {

// Meshes a case given as JSON text; expects failure with the code and message parts.
void expectCaseFails(const std::string& json, const std::string& code, const std::string& part,
                     const std::string& extra = "") {
  const std::string in = tmp("case.json"), out = tmp("case_out.mesh");
  std::remove(out.c_str());
  writeFile(in, json);
  const CliRun r = run("mesh " + in + " -o " + out + " " + extra);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("error " + code + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
  EXPECT_FALSE(exists(out));
}

const char* kSquare = R"({"type": "polyline", "points": [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]})";

std::string withHoles(const std::string& holes) {
  return std::string(R"({"domain": {"outer": [)") + kSquare + R"(], "holes": )" + holes +
         R"(}, "controlSpace": {"hmax": 0.5}})";
}

}  // namespace

TEST(CliPipeline, BadDomainsAreNamed) {
  expectCaseFails(
      R"({"domain": {"outer": [{"type": "line", "p1": [0, 0], "p2": [1, 0]}, {"type": "line", "p1": [1, 0], "p2": [1, 1]}]},
                      "controlSpace": {"hmax": 0.1}})",
      "OPEN_CONTOUR", "outer");
  expectCaseFails(R"({"domain": {"outer": [{"type": "polyline", "points": [[0, 0], [2, 2], [2, 0], [0, 2], [0, 0]]}]},
                      "controlSpace": {"hmax": 0.1}})",
                  "SELF_INTERSECTING_CONTOUR", "outer");
  expectCaseFails(withHoles(R"([[{"type": "circle", "center": [10, 10], "radius": 1}]])"), "HOLE_OUTSIDE_DOMAIN",
                  "holes[0]");
  expectCaseFails(withHoles(R"([[{"type": "circle", "center": [1.5, 2], "radius": 0.8}],
                                [{"type": "circle", "center": [2.5, 2], "radius": 0.8}]])"),
                  "SELF_INTERSECTING_CONTOUR", "holes[1]");
  expectCaseFails(std::string(R"({"domain": {"outer": [)") + kSquare + R"(,
                      {"type": "line", "p1": [0, 0], "p2": [0, 0]}]}, "controlSpace": {"hmax": 0.5}})",
                  "ZERO_LENGTH_CURVE", "outer");
}

TEST(CliPipeline, BadJsonAndBudgetAreNamed) {
  expectCaseFails("{\"domain\": ", "PARSE_ERROR", "malformed JSON");
  expectCaseFails(std::string(R"({"domain": {"outer": [)") + kSquare + R"(]}, "controlSpace": {"hmax": 0.5},
                      "sources": [{"type": "analytic", "field": "expression", "h1": "0.1 * (x + "}]})",
                  "PARSE_ERROR", "sources[0].h1");
  expectCaseFails(std::string(R"({"domain": {"outer": [)") + kSquare + R"(]}, "controlSpace": {"hmax": 0.5},
                      "sources": [{"type": "nodes", "points": [[1, 1]], "metrics": []}]})",
                  "PARSE_ERROR", "sources[0].metrics");
  expectCaseFails(std::string(R"({"domain": {"outer": [)") + kSquare + R"(]}, "controlSpace": {"hmax": 0.05}})",
                  "ELEMENT_BUDGET_EXCEEDED", "", "--max-elements 100");
}

TEST(CliPipeline, RemeshBadSolutions) {
  const std::string mesh = tmp("in.mesh"), sol = tmp("in.sol"), out = tmp("remesh_out.mesh");
  std::remove(out.c_str());
  writeFile(mesh,
            "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
            "Triangles\n2\n1 2 3 0\n1 3 4 0\nEnd\n");
  // A non-SPD tensor (m11 m12 m22 with m12^2 > m11 m22).
  writeFile(sol,
            "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n4\n1 3\n100 0 100\n100 500 100\n100 0 100\n100 0 "
            "100\nEnd\n");
  CliRun r = run("remesh " + mesh + " -sol " + sol + " -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("INVALID_METRIC"), std::string::npos) << r.err;
  // Count mismatch.
  writeFile(sol, "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n3\n1 1\n0.1\n0.1\n0.1\nEnd\n");
  r = run("remesh " + mesh + " -sol " + sol + " -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("3 values but the mesh has 4 vertices"), std::string::npos) << r.err;
  // Malformed .sol.
  writeFile(sol, "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\nfour\n");
  r = run("remesh " + mesh + " -sol " + sol + " -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("PARSE_ERROR"), std::string::npos) << r.err;
  // Budget.
  writeFile(sol, "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n4\n1 1\n0.01\n0.01\n0.01\n0.01\nEnd\n");
  r = run("remesh " + mesh + " -sol " + sol + " -o " + out + " --max-elements 50");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("ELEMENT_BUDGET_EXCEEDED"), std::string::npos) << r.err;
  // hgrad below 1 is a usage error.
  EXPECT_EQ(run("remesh " + mesh + " -sol " + sol + " -o " + out + " -hgrad 0.5").code, 2);
  EXPECT_FALSE(exists(out));
  // And a good run with hgrad.
  r = run("remesh " + mesh + " -sol " + sol + " -o " + out + " -hgrad 1.3 --stats");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists(out));
  std::remove(out.c_str());
}

// The CLI starts itself again with glibc's malloc on transparent huge pages (where the
// kernel offers them) unless GLIBC_TUNABLES already names the tunable; -v 1 says which.
// The mesh is the same bytes either way.
TEST(CliPipeline, RemeshRunsOnHugePagesUnlessTold) {
  const std::string mesh = tmp("in.mesh"), sol = tmp("in.sol"), out = tmp("out.mesh");
  writeFile(mesh,
            "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
            "Triangles\n2\n1 2 3 0\n1 3 4 0\nEnd\n");
  writeFile(sol, "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n4\n1 1\n0.05\n0.05\n0.05\n0.02\nEnd\n");
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  const bool offered = std::getline(thp, mode) && mode.find("[never]") == std::string::npos;
  CliRun r = run("remesh " + mesh + " -sol " + sol + " -o " + out + " -v 1", "env -u GLIBC_TUNABLES");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find(std::string("transparent huge pages ") + (offered ? "on" : "off")), std::string::npos) << r.err;
  const std::string onPages = slurp(out);
  r = run("remesh " + mesh + " -sol " + sol + " -o " + out + " -v 1", "GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("transparent huge pages off"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(out), onPages);
  EXPECT_GT(onPages.size(), 100u);
}

TEST(CliPipeline, StatsAndSvg) {
  const std::string out = tmp("dr2.svg");
  const CliRun r = run("mesh " + example("fig7_rect_holes_dr2.json") + " -o " + out + " --stats");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"triangles", "edgeLength", "quality", "largestNeighbourSizeRatio", "pipelineSeconds",
                          "boundaryUpdates", "timings", "controlElements"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_GE(j["boundaryUpdates"]["rounds"].get<int>(), 1);
  EXPECT_EQ(j["inverted"], 0);
  const std::string svg = slurp(out);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  std::remove(out.c_str());
}

TEST(CliPipeline, SurfaceSvgViews) {
  // A surface case as an SVG: 3D view (one polygon per element, coloured by 3D quality),
  // the parameter plane with control-space glyphs, and bad --svg-view values rejected.
  const std::string out = tmp("sphere.svg"), uv = tmp("sphere_uv.svg");
  CliRun r = run("mesh " + example("surface/surface_sphere.json") + " -o " + out + " --svg-view -60,25 --stats");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const std::string svg = slurp(out);
  size_t polygons = 0;
  for (size_t p = svg.find("<polygon"); p != std::string::npos; p = svg.find("<polygon", p + 1)) ++polygons;
  EXPECT_EQ(polygons, j["triangles"].get<size_t>());
  r = run("mesh " + example("surface/surface_sphere.json") + " -o " + uv + " --svg-uv --svg-control-space");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string svgUv = slurp(uv);
  EXPECT_NE(svgUv.find("fill=\"none\""), std::string::npos);  // the glyph overlay
  r = run("mesh " + example("surface/surface_sphere.json") + " -o " + out + " --svg-view 30");
  EXPECT_EQ(r.code, 2);
  std::remove(out.c_str());
  std::remove(uv.c_str());
}

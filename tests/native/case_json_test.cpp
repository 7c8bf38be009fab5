#include <gtest/gtest.h>

#include <dirent.h>

#include <string>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/io/case_json.h"

using namespace anisomesh;

namespace {

const char* kMinimal = R"({
  "domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]},
  "controlSpace": {"hmax": 0.1}
})";

// Parses text and checks the error code and a message fragment.
void expectError(const std::string& text, ErrorCode code, const std::string& fragment) {
  try {
    parseCaseJson(text);
    FAIL() << "accepted: " << text;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// kMinimal with one more top-level entry.
std::string withTop(const std::string& entry) {
  return R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]},
            "controlSpace": {"hmax": 0.1}, )" +
         entry + "}";
}

}  // namespace

TEST(CaseJson, MinimalDefaults) {
  const CaseSpec s = parseCaseJson(kMinimal);
  ASSERT_EQ(s.domain.outer.curves.size(), 1u);
  EXPECT_STREQ(s.domain.outer.curves[0].curve->typeName(), "arc");
  EXPECT_EQ(s.domain.outer.curves[0].curve->ref(), 1);  // default ref of the outer contour
  EXPECT_EQ(s.controlSpace.kind, "quadtree");
  EXPECT_EQ(s.controlSpace.hmax, 0.1);
  EXPECT_EQ(s.controlSpace.hmin, 0.0);
  EXPECT_FALSE(s.controlSpace.gradation.has_value());
  EXPECT_EQ(s.controlSpace.interpolation, "bilinear");
  EXPECT_TRUE(s.sources.empty());
  EXPECT_FALSE(s.options.quads);
  EXPECT_EQ(s.options.maxElements, 50000000);
}

TEST(CaseJson, AllCurveAndSourceKinds) {
  const CaseSpec s = parseCaseJson(R"({
    "domain": {
      "outer": [
        {"type": "line", "p1": [0, 0], "p2": [4, 0], "ref": 3},
        {"type": "arc", "points": [[4, 0], [4.5, 1], [4, 2]]},
        {"type": "polyline", "points": [[4, 2], [3, 3], [2, 2]]},
        {"type": "bspline", "points": [[2, 2], [1.5, 2.5], [1, 2], [0.5, 2.5], [0, 2]]},
        {"type": "bezier", "points": [[0, 2], [-1, 1.5], [1, 0.5], [0, 0]], "ref": 9}
      ],
      "holes": [
        [{"type": "arc", "center": [2, 1], "radius": 0.3, "start": 0, "end": 3.141592653589793},
         {"type": "arc", "center": [2, 1], "radius": 0.3, "start": 3.141592653589793, "end": 6.283185307179586}]
      ]
    },
    "controlSpace": {"kind": "background", "hmin": 0.01, "hmax": 0.5, "gradation": 2.5, "interpolation": "inverse_distance"},
    "sources": [
      {"type": "radial", "center": [1, 1], "metric": {"alpha": 0.5, "h1": 0.02, "h2": 0.2}, "radius": 0.3},
      {"type": "segment", "p1": [0, 0], "p2": [4, 0], "metric": {"h1": 0.05}, "radius": 0.1},
      {"type": "analytic", "field": "boundary_layer", "p1": [0, 0], "p2": [1, 0], "h0": 0.001, "hTangent": 0.1, "thickness": 0.2},
      {"type": "analytic", "field": "shear_layer_circle", "center": [2, 1], "radius": 0.5, "h0": 0.01, "hTangent": 0.1, "thickness": 0.05},
      {"type": "analytic", "field": "point", "center": [3, 1], "h0": 0.01, "growth": 0.2}
    ],
    "options": {"quads": true, "allQuads": true, "maxElements": 1000}
  })");
  const auto& c = s.domain.outer.curves;
  ASSERT_EQ(c.size(), 5u);
  EXPECT_STREQ(c[0].curve->typeName(), "line");
  EXPECT_EQ(c[0].curve->ref(), 3);
  EXPECT_STREQ(c[1].curve->typeName(), "arc");
  EXPECT_EQ(c[1].curve->ref(), 1);
  EXPECT_STREQ(c[2].curve->typeName(), "polyline");
  EXPECT_STREQ(c[3].curve->typeName(), "bspline");
  EXPECT_STREQ(c[4].curve->typeName(), "bezier");
  EXPECT_EQ(c[4].curve->ref(), 9);
  ASSERT_EQ(s.domain.holes.size(), 1u);
  EXPECT_EQ(s.domain.holes[0].curves[0].curve->ref(), 2);  // default ref of holes[0]
  EXPECT_LT((c[1].curve->end() - Vec2(4, 2)).norm(), 1e-12);
  EXPECT_EQ(s.controlSpace.kind, "background");
  EXPECT_EQ(*s.controlSpace.gradation, 2.5);
  EXPECT_EQ(s.controlSpace.interpolation, "inverse_distance");
  ASSERT_EQ(s.sources.size(), 5u);
  EXPECT_EQ(s.sources[0].type, SourceType::Radial);
  EXPECT_EQ(s.sources[0].metric.h2, 0.2);
  EXPECT_EQ(s.sources[1].type, SourceType::Segment);
  EXPECT_EQ(s.sources[1].metric.h2, 0.05);  // h2 defaults to h1
  EXPECT_EQ(s.sources[2].analytic.field, "boundary_layer");
  EXPECT_EQ(s.sources[3].analytic.radius, 0.5);
  EXPECT_EQ(s.sources[4].analytic.growth, 0.2);
  EXPECT_TRUE(s.options.quads);
  EXPECT_TRUE(s.options.allQuads);
  EXPECT_EQ(s.options.maxElements, 1000);
  EXPECT_NO_THROW(validateDomain(s.domain));
}

TEST(CaseJson, MalformedJson) {
  expectError("{\"domain\": ", ErrorCode::ParseError, "malformed JSON");
  expectError("[1, 2]", ErrorCode::ParseError, "(root): expected an object");
}

TEST(CaseJson, MissingFieldsNamePath) {
  expectError(R"({"controlSpace": {"hmax": 1}})", ErrorCode::ParseError, "domain: missing field");
  expectError(R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]}})", ErrorCode::ParseError,
              "controlSpace: missing field");
  expectError(R"({"domain": {"outer": [{"type": "line", "p1": [0, 0]}]}, "controlSpace": {"hmax": 1}})",
              ErrorCode::ParseError, "domain.outer[0].p2: missing field");
  expectError(withTop(R"("sources": [{"type": "radial", "center": [0, 0], "metric": {"h1": 1}}])"),
              ErrorCode::ParseError, "sources[0].radius: missing field");
  expectError(R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]}, "controlSpace": {}})",
              ErrorCode::ParseError, "controlSpace.hmax: missing field");
}

TEST(CaseJson, WrongTypesNamePath) {
  expectError(
      withTop(
          R"("sources": [{"type": "point"}, {"type": "analytic", "field": "point", "center": [0, 0], "h0": 1, "growth": 0},
                                     {"type": "radial", "center": [0, 0], "metric": {"h1": 1}, "radius": "big"}])"),
      ErrorCode::ParseError, "sources[0].type: unknown source type 'point'");
  expectError(withTop(R"("sources": [{"type": "analytic", "field": "point", "center": [0, 0], "h0": 1, "growth": 0},
                                     {"type": "analytic", "field": "point", "center": [0, 0], "h0": 1, "growth": 0},
                                     {"type": "radial", "center": [0, 0], "metric": {"h1": 1}, "radius": "big"}])"),
              ErrorCode::ParseError, "sources[2].radius: expected a number, got string");
  expectError(
      R"({"domain": {"outer": [{"type": "line", "p1": [0, 0, 0], "p2": [1, 0]}]}, "controlSpace": {"hmax": 1}})",
      ErrorCode::ParseError, "domain.outer[0].p1: expected a point [x, y]");
  expectError(R"({"domain": {"outer": {"type": "line"}}, "controlSpace": {"hmax": 1}})", ErrorCode::ParseError,
              "domain.outer: expected an array of curves");
  expectError(withTop(R"("options": {"quads": 1})"), ErrorCode::ParseError, "options.quads: expected true or false");
  expectError(withTop(R"("options": {"maxElements": 1.5})"), ErrorCode::ParseError,
              "options.maxElements: expected an integer");
  expectError(
      R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1, "ref": "a"}]}, "controlSpace": {"hmax": 1}})",
      ErrorCode::ParseError, "domain.outer[0].ref: expected an integer");
  expectError(R"({"domain": {"outer": [], "holes": 3}, "controlSpace": {"hmax": 1}})", ErrorCode::ParseError,
              "domain.outer: expected at least one curve");
}

TEST(CaseJson, UnknownNamesAreRejected) {
  expectError(R"({"domain": {"outer": [{"type": "spiral"}]}, "controlSpace": {"hmax": 1}})", ErrorCode::ParseError,
              "domain.outer[0].type: unknown curve type 'spiral'");
  expectError(withTop(R"("sources": [{"type": "radial", "center": [0, 0], "metric": {"h1": 1}, "raduis": 1}])"),
              ErrorCode::ParseError, "sources[0].raduis: unknown field");
  expectError(withTop(R"("sources": [{"type": "analytic", "field": "vortex"}])"), ErrorCode::ParseError,
              "sources[0].field: unknown analytic field 'vortex'");
  expectError(
      R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]}, "controlSpace": {"hmax": 1, "kind": "octree"}})",
      ErrorCode::ParseError, "controlSpace.kind: expected \"quadtree\" or \"background\"");
  expectError(
      R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]}, "controlSpace": {"hmax": 1, "interpolation": "cubic"}})",
      ErrorCode::ParseError, "controlSpace.interpolation");
}

TEST(CaseJson, ValuesOutOfRange) {
  expectError(
      R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": -1}]}, "controlSpace": {"hmax": 1}})",
      ErrorCode::InvalidArgument, "domain.outer[0].radius: must be positive");
  expectError(
      R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]}, "controlSpace": {"hmax": 1, "gradation": 0.5}})",
      ErrorCode::InvalidArgument, "controlSpace.gradation: must be >= 1 or null");
  expectError(
      R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]}, "controlSpace": {"hmax": 1, "hmin": 2}})",
      ErrorCode::InvalidArgument, "controlSpace.hmin: must be in [0, hmax]");
  expectError(withTop(R"("sources": [{"type": "radial", "center": [0, 0], "metric": {"h1": 0}, "radius": 1}])"),
              ErrorCode::InvalidArgument, "sources[0].metric.h1: must be positive");
  expectError(
      R"({"domain": {"outer": [{"type": "arc", "points": [[0, 0], [1, 1], [2, 2]]}]}, "controlSpace": {"hmax": 1}})",
      ErrorCode::InvalidArgument, "domain.outer[0]: arc through");
  expectError(
      R"({"domain": {"outer": [{"type": "bspline", "points": [[0, 0], [1, 1], [2, 2]]}]}, "controlSpace": {"hmax": 1}})",
      ErrorCode::ParseError, "domain.outer[0].points: expected at least 4 points, got 3");
}

TEST(CaseJson, NullGradationMeansNone) {
  const CaseSpec s = parseCaseJson(R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]},
                                       "controlSpace": {"hmax": 1, "gradation": null}})");
  EXPECT_FALSE(s.controlSpace.gradation.has_value());
}

TEST(CaseJson, UnreadableFile) {
  try {
    readCaseFile("/nonexistent/case.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::IoError);
  }
}

TEST(CaseJson, EveryExampleParsesAndValidates) {
  const std::string dir = std::string(ANISOMESH_SOURCE_DIR) + "/examples";
  DIR* d = opendir(dir.c_str());
  ASSERT_NE(d, nullptr) << dir;
  std::vector<std::string> files;
  while (dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (name.size() > 5 && name.substr(name.size() - 5) == ".json") files.push_back(name);
  }
  closedir(d);
  EXPECT_GE(files.size(), 6u);
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    CaseSpec s;
    ASSERT_NO_THROW(s = readCaseFile(dir + "/" + f));
    EXPECT_NO_THROW(validateDomain(s.domain));
  }
}

// One reader for planar and surface cases: the same field gets the same check and the same
// message in both (they used to differ: e.g. only the planar reader required a source's
// radius, and the messages differed).
TEST(CaseJson, PlanarAndSurfaceReadersCheckFieldsAlike) {
  auto errorOf = [](auto parse, const std::string& text) -> std::pair<ErrorCode, std::string> {
    try {
      parse(text);
    } catch (const Error& e) {
      return {e.code(), e.what()};
    } catch (const std::exception& e) {
      return {ErrorCode::InvalidArgument, std::string("not an anisomesh::Error: ") + e.what()};
    }
    return {ErrorCode::InvalidArgument, "accepted"};
  };
  auto planar = [](const std::string& t) { parseCaseJson(t); };
  auto surface = [](const std::string& t) { parseSurfaceCaseJson(t); };
  // 1e999 overflows a double: nlohmann throws out_of_range (not parse_error), which used to
  // escape both readers uncoded; now a ParseError in both kinds of case.
  const auto p = errorOf(planar, R"({"domain": {"outer": [{"type": "circle", "center": [1e999, 0], "radius": 1}]},
                                    "controlSpace": {"hmax": 0.1}})");
  const auto s = errorOf(surface, R"({"patches": [{"surface": {"type": "plane"},
      "outer": [{"type": "circle", "center": [1e999, 0.5], "radius": 0.2}]}]})");
  EXPECT_EQ(p.first, ErrorCode::ParseError) << p.second;
  EXPECT_EQ(s.first, ErrorCode::ParseError) << s.second;
  EXPECT_NE(p.second.find("(root): malformed JSON"), std::string::npos) << p.second;
  EXPECT_NE(s.second.find("(root): malformed JSON"), std::string::npos) << s.second;
  EXPECT_FALSE(isSurfaceCaseJson(R"({"patches": [1e999]})"));
  // A source without its radius: the same missing-field error in both.
  const auto ps =
      errorOf(planar, withTop(R"("sources": [{"type": "radial", "center": [0, 0], "metric": {"h1": 0.1}}])"));
  const auto ss = errorOf(surface, R"({"patches": [{"surface": {"type": "plane"},
      "sources": [{"type": "radial", "center": [0.5, 0.5], "metric": {"h1": 0.1}}]}]})");
  EXPECT_EQ(ps.first, ErrorCode::ParseError) << ps.second;
  EXPECT_EQ(ss.first, ErrorCode::ParseError) << ss.second;
  EXPECT_NE(ps.second.find("sources[0].radius: missing field"), std::string::npos) << ps.second;
  EXPECT_NE(ss.second.find("patches[0].sources[0].radius: missing field"), std::string::npos) << ss.second;
  // A surface case lists only the source types it supports.
  const auto st = errorOf(surface, R"({"patches": [{"surface": {"type": "plane"},
      "sources": [{"type": "nodes", "points": [[0.5, 0.5]], "metrics": [{"h1": 0.1}]}]}]})");
  EXPECT_NE(st.second.find("unknown source type 'nodes' (expected radial, segment, polyline or curve)"),
            std::string::npos)
      << st.second;
}

// Error messages in the user's words: numbers as given (not "5.000000"), JSON syntax errors
// with line and column but without the parser's internals.
#include <gtest/gtest.h>

#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/core/number_text.h"
#include "anisomesh/io/run_case.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {
namespace {

std::string messageOf(const std::function<void()>& f, ErrorCode code) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(Messages, NumberTextIsTheShortestRoundTrip) {
  EXPECT_EQ(numberText(5), "5");
  EXPECT_EQ(numberText(-5), "-5");
  EXPECT_EQ(numberText(0.1), "0.1");
  EXPECT_EQ(numberText(1e-300), "1e-300");
  EXPECT_EQ(numberText(0.30000000000000004), "0.30000000000000004");
  EXPECT_EQ(numberText(1.0 / 3), "0.3333333333333333");
  EXPECT_EQ(numberText(0), "0");
}

TEST(Messages, MetricSizesPrintAsGiven) {
  const std::string m = messageOf([] { Metric::isotropic(-5); }, ErrorCode::InvalidMetric);
  EXPECT_NE(m.find("got -5"), std::string::npos) << m;
  EXPECT_EQ(m.find("5.000000"), std::string::npos) << m;
}

TEST(Messages, PlanarCaseNumbersPrintAsGiven) {
  const std::string m = messageOf(
      [] {
        runCase(R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]},
                    "controlSpace": {"hmax": 0.5, "gradation": 0.5}})");
      },
      ErrorCode::InvalidArgument);
  EXPECT_EQ(m.find("000000"), std::string::npos) << m;
}

TEST(Messages, JsonSyntaxErrorsNameLineAndColumnWithoutParserInternals) {
  for (const char* text : {"{\"domain\": tru,\n}", "{\"patches\": [", "", "{\"a\": 1,,}"}) {
    const std::string m = messageOf([&] { runCase(text); }, ErrorCode::ParseError);
    EXPECT_EQ(m.find("json.exception"), std::string::npos) << m;
    EXPECT_EQ(m.find("parse_error"), std::string::npos) << m;
    EXPECT_NE(m.find("malformed JSON at line "), std::string::npos) << m;
    EXPECT_NE(m.find("column"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace anisomesh

// CLI adapt: -field and -sol runs write the mesh, the transferred fields beside it and the
// iteration report; bad input gives coded errors (exit 1) or usage errors (exit 2).
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "anisomesh/io/medit.h"
#include "cli_test_util.h"

using namespace clitest;

namespace {
std::string square() { return example("adaptation/square.mesh"); }
}  // namespace

TEST(CliAdapt, FieldRunWritesMeshSolAndReport) {
  const std::string out = tmp("a.mesh"), sol = tmp("a.sol"), svg = tmp("a.svg");
  const CliRun r = run("adapt " + square() + " -field 'tanh(30*(x+y-1))' -nv 800 -iterations 2 -hmax 0.2 -o " + out +
                       " -svg " + svg + " --stats");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["iterations"].size(), 2u);
  const anisomesh::Mesh m = anisomesh::readMeditFile(out);
  const anisomesh::SolData s = anisomesh::readSolFile(sol);
  EXPECT_EQ(s.count(), m.vertexCount());
  EXPECT_EQ(j["iterations"][1]["vertices"].get<int>(), m.vertexCount());
  EXPECT_NEAR(m.vertexCount(), 800, 160);  // (the 10% rule over longer loops: adapt_metric_test)
  EXPECT_GT(j["iterations"][1]["errorLinf"].get<double>(), 0.0);
  EXPECT_NE(slurp(svg).find("<svg"), std::string::npos);
  // The written field feeds a -sol run (transfer instead of re-sampling).
  const std::string out2 = tmp("b.mesh");
  const CliRun r2 = run("adapt " + out + " -sol " + sol + " -err 0.01 -iterations 1 -o " + out2);
  ASSERT_EQ(r2.code, 0) << r2.err;
  EXPECT_NE(r2.out.find("iteration 1: "), std::string::npos);
  EXPECT_EQ(anisomesh::readSolFile(tmp("b.sol")).count(), anisomesh::readMeditFile(out2).vertexCount());
}

TEST(CliAdapt, BadInputIsReported) {
  const std::string out = tmp("bad.mesh");
  auto expect = [&](const std::string& args, int code, const std::string& part) {
    std::remove(out.c_str());
    const CliRun r = run("adapt " + args + " -o " + out);
    EXPECT_EQ(r.code, code) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(part), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(exists(out)) << args;
  };
  const std::string sol = tmp("three.sol");
  writeFile(sol, "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n3\n1 1\n1\n2\n3\nEnd\n");
  expect(square() + " -sol " + sol + " -nv 500", 1, "error INVALID_ARGUMENT: ");
  const std::string nan = tmp("nan.sol");
  std::string text = "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n782\n1 1\n";
  for (int i = 0; i < 782; ++i) text += i == 7 ? "nan\n" : "1\n";
  writeFile(nan, text + "End\n");
  const CliRun probe = run("adapt " + square() + " -sol " + nan + " -nv 500 -o " + out);
  EXPECT_NE(probe.code, 0);  // a parse error or a non-finite value, both coded
  EXPECT_NE(probe.err.find("error "), std::string::npos) << probe.err;
  expect(square() + " -field 'log(x)' -nv 500", 1, "not finite at vertex");
  expect(square() + " -field 'x^2' -nv 1e9", 1, "error ELEMENT_BUDGET_EXCEEDED: ");
  expect(square() + " -field 'x^2+' -nv 500", 1, "error PARSE_ERROR: ");
  expect(square() + " -field 'x^2' -nv 500 -err 0.1", 2, "one of -err E or -nv N");
  expect(square() + " -nv 500", 2, "-sol or by -field");
  expect(square() + " -field 'x' -nv 500 -norm 3", 2, "-norm expects 1, 2 or inf");
  expect(square() + " -field 'x' -nv 500 -hgrad 0.5", 2, "-hgrad expects");
}

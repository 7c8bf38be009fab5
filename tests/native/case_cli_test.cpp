// CLI tests that need no mesher: usage errors and bad input rejected before meshing.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_test_util.h"

using namespace clitest;

TEST(CaseCli, VersionAndHelp) {
  const CliRun r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("anisomesh"), std::string::npos);
  // The version is written once, in package.json.
  const std::string package = slurp(std::string(ANISOMESH_SOURCE_DIR) + "/package.json");
  const std::size_t at = package.find("\"version\": \"");
  ASSERT_NE(at, std::string::npos);
  const std::string version = package.substr(at + 12, package.find('"', at + 12) - at - 12);
  EXPECT_EQ(r.out, "anisomesh " + version + "\n");
  EXPECT_EQ(run("--help").code, 0);
}

TEST(CaseCli, UsageErrorsExit2) {
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("frobnicate").code, 2);
  const CliRun noOut = run("mesh case.json");
  EXPECT_EQ(noOut.code, 2);
  EXPECT_NE(noOut.err.find("missing -o OUT"), std::string::npos) << noOut.err;
  EXPECT_EQ(run("mesh").code, 2);
  EXPECT_EQ(run("mesh case.json -o out.mesh --bogus").code, 2);
  EXPECT_EQ(run("mesh case.json -o out.mesh --max-elements many").code, 2);
  EXPECT_EQ(run("mesh case.json -o").code, 2);
  const CliRun ext = run("mesh case.json -o out.stl");
  EXPECT_EQ(ext.code, 2);
  EXPECT_NE(ext.err.find(".mesh, .meshb, .vtk, .obj or .msh"), std::string::npos) << ext.err;
  EXPECT_EQ(run("remesh in.mesh -o out.mesh").code, 2);  // no -sol
  EXPECT_EQ(run("remesh in.mesh -sol in.sol -o out.mesh -hmin abc").code, 2);
  EXPECT_EQ(run("remesh in.mesh -sol in.sol -o out.mesh -hmin 2 -hmax 1").code, 2);
}

TEST(CaseCli, MissingCaseFileIsIoError) {
  const CliRun r = run("mesh /nonexistent/case.json -o " + tmp("never.mesh"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("anisomesh: error IO_ERROR: "), std::string::npos) << r.err;
}

TEST(CaseCli, MalformedJsonExit1NoOutput) {
  const std::string in = tmp("bad.json"), out = tmp("bad_out.mesh");
  std::remove(out.c_str());
  writeFile(in, "{\"domain\": {\"outer\": [ }");
  const CliRun r = run("mesh " + in + " -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("anisomesh: error PARSE_ERROR: "), std::string::npos) << r.err;
  EXPECT_FALSE(exists(out));
}

TEST(CaseCli, WrongFieldTypeNamesPath) {
  const std::string in = tmp("badtype.json"), out = tmp("badtype_out.vtk");
  writeFile(in, R"({"domain": {"outer": [{"type": "circle", "center": [0, 0], "radius": 1}]},
                   "controlSpace": {"hmax": 0.1},
                   "sources": [{"type": "radial", "center": [0, 0], "metric": {"h1": 0.1}, "radius": [1]}]})");
  const CliRun r = run("mesh " + in + " -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("sources[0].radius: expected a number"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(out));
}

TEST(CaseCli, InvalidDomainExit1BeforeMeshing) {
  const std::string in = tmp("open.json"), out = tmp("open_out.mesh");
  std::remove(out.c_str());
  writeFile(in, R"({"domain": {"outer": [{"type": "line", "p1": [0, 0], "p2": [1, 0]},
                                         {"type": "line", "p1": [1, 0], "p2": [1, 1]}]},
                   "controlSpace": {"hmax": 0.1}})");
  const CliRun r = run("mesh " + in + " -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("error OPEN_CONTOUR: "), std::string::npos) << r.err;
  EXPECT_FALSE(exists(out));
}

TEST(CaseCli, RemeshBadInputsExit1) {
  const std::string mesh = tmp("in.mesh"), sol = tmp("in.sol"), out = tmp("remesh_out.mesh");
  std::remove(out.c_str());
  writeFile(mesh,
            "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nTriangles\n1\n1 2 3 0\nEnd\n");
  writeFile(sol, "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n2\n1 1\n0.1\n0.1\nEnd\n");
  const CliRun mismatch = run("remesh " + mesh + " -sol " + sol + " -o " + out);
  EXPECT_EQ(mismatch.code, 1);
  EXPECT_NE(mismatch.err.find("the solution has 2 values but the mesh has 3 vertices"), std::string::npos)
      << mismatch.err;
  writeFile(mesh, "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 0\n1 0\n");
  const CliRun bad = run("remesh " + mesh + " -sol " + sol + " -o " + out);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("error PARSE_ERROR: Medit mesh line 6: expected the reference of vertex 2"), std::string::npos)
      << bad.err;
  EXPECT_EQ(run("remesh /nonexistent.mesh -sol " + sol + " -o " + out).code, 1);
  EXPECT_FALSE(exists(out));
}

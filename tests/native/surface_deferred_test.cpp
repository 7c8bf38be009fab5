// A surface run made with stats false leaves its 3D measures to caseRunStats(): the mesh
// comes first, and the report made afterwards is the one a run with its stats gives.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "anisomesh/io/run_case.h"

using namespace anisomesh;

namespace {

std::string readText(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The report without its timings (they differ between runs).
nlohmann::json untimed(nlohmann::json stats) {
  for (const char* k : {"secondsTotal", "curvatureSeconds", "controlSpaceSeconds"}) stats.erase(k);
  return stats;
}

}  // namespace

TEST(SurfaceDeferred, ReportAfterTheMeshIsTheRunsReport) {
  for (const char* name : {"surface_p2_holes", "surface_two_patch_c", "surface_torus"})
    for (const bool quads : {false, true}) {
      SCOPED_TRACE(std::string(name) + (quads ? " quads" : ""));
      const std::string text = readText(std::string(ANISOMESH_SOURCE_DIR) + "/examples/surface/" + name + ".json");
      RunCaseOptions o;
      o.quads = quads;
      const CaseRun full = runCase(text, o);
      o.stats = false;
      const CaseRun quick = runCase(text, o);
      EXPECT_TRUE(quick.stats.is_null());
      ASSERT_NE(quick.surfaceReport, nullptr);
      EXPECT_EQ(quick.mesh.triangles, full.mesh.triangles);
      EXPECT_EQ(quick.mesh.quads, full.mesh.quads);
      EXPECT_EQ(quick.mesh.points, full.mesh.points);
      // The per-element values are there at once (the colouring), the same as the run's.
      EXPECT_EQ(quick.elementQuality, full.elementQuality);
      ASSERT_EQ(quick.edgeLengths.size(), full.edgeLengths.size());
      for (size_t e = 0; e < full.edgeLengths.size(); ++e) {
        EXPECT_EQ(quick.edgeLengths[e].a, full.edgeLengths[e].a);
        EXPECT_EQ(quick.edgeLengths[e].b, full.edgeLengths[e].b);
        EXPECT_EQ(quick.edgeLengths[e].length, full.edgeLengths[e].length);
      }
      // The chord deviations are not made yet; the report makes them (once).
      EXPECT_NE(quick.surfaceReport->deferred, nullptr);
      EXPECT_EQ(quick.surfaceReport->quality.edges, 0);
      EXPECT_EQ(untimed(caseRunStats(quick)).dump(), untimed(full.stats).dump());
      EXPECT_EQ(quick.surfaceReport->deferred, nullptr);
      EXPECT_EQ(untimed(caseRunStats(quick)).dump(), untimed(full.stats).dump());
      // Without the per-element values first: the same report.
      o.elementMeasures = false;
      const CaseRun bare = runCase(text, o);
      EXPECT_TRUE(bare.elementQuality.empty());
      EXPECT_EQ(untimed(caseRunStats(bare)).dump(), untimed(full.stats).dump());
    }
}

// VTU (VTK XML) of a case run: point data (ref, metric tensor, requested sizes) and cell data
// (ref, quality, edge-length min/max) with one value per point / cell, values equal to the
// run's own measures; meshio reads the file where installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "anisomesh/io/case_vtu.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/run_case.h"
#include "anisomesh/mesh/quality.h"

using namespace anisomesh;

namespace {

CaseRun runExample(const std::string& example, bool quads) {
  RunCaseOptions o;
  o.quads = quads;
  return runCase(readTextFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + example), o);
}

// The numbers of the DataArray named name.
std::vector<double> dataArray(const std::string& vtu, const std::string& name) {
  const std::string key = "Name=\"" + name + "\"";
  const size_t at = vtu.find(key);
  if (at == std::string::npos) return {};
  const size_t begin = vtu.find('>', at) + 1, end = vtu.find("</DataArray>", begin);
  std::istringstream in(vtu.substr(begin, end - begin));
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

// A Python with meshio (Debian's python3-meshio is for /usr/bin/python3), or "".
std::string vtuMeshioPython() {
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (std::system((std::string(py) + " -c 'import meshio' >/dev/null 2>&1").c_str()) == 0) return py;
  return "";
}

}  // namespace

TEST(IoVtu, PlanarFieldsHaveOneValuePerPointAndCellAndMatchTheMeasures) {
  const CaseRun run = runExample("fig7_rect_holes_dr2.json", true);
  const std::string vtu = caseRunVtu(run);
  const Mesh& m = run.mesh;
  const size_t nv = m.points.size(), cells = m.edges.size() + m.triangles.size() + m.quads.size();
  EXPECT_EQ(dataArray(vtu, "Points").size(), 3 * nv);
  EXPECT_EQ(dataArray(vtu, "metric").size(), 9 * nv);
  EXPECT_EQ(dataArray(vtu, "requestedSize").size(), 2 * nv);
  EXPECT_EQ(dataArray(vtu, "ref").size(), nv);  // the first "ref" array: point data
  EXPECT_EQ(dataArray(vtu, "types").size(), cells);
  const std::vector<double> quality = dataArray(vtu, "quality");
  ASSERT_EQ(quality.size(), cells);
  ElementMeasures items;
  measureQuality(m, *run.finalSpace, &items);
  for (size_t i = 0; i < items.quality.size(); ++i) ASSERT_EQ(quality[m.edges.size() + i], items.quality[i]) << i;
  const std::vector<double> lo = dataArray(vtu, "edgeLengthMin"), hi = dataArray(vtu, "edgeLengthMax");
  ASSERT_EQ(lo.size(), cells);
  for (size_t i = 0; i < cells; ++i) {
    ASSERT_GT(lo[i], 0.3) << i;
    ASSERT_LE(lo[i], hi[i]) << i;
  }
  // The metric tensor at vertex 0 is the control space's there.
  const Mat2 t = run.finalSpace->metricAt(Vec2(m.points[0].x(), m.points[0].y())).tensor();
  const std::vector<double> metric = dataArray(vtu, "metric");
  EXPECT_EQ(metric[0], t(0, 0));
  EXPECT_EQ(metric[1], t(0, 1));
  EXPECT_EQ(metric[4], t(1, 1));
}

TEST(IoVtu, SurfaceRunCarries3dQuality) {
  const CaseRun run = runExample("surface/surface_sphere.json", false);
  const std::string vtu = caseRunVtu(run);
  const std::vector<double> quality = dataArray(vtu, "quality");
  ASSERT_EQ(quality.size(), run.mesh.edges.size() + run.mesh.triangles.size() + run.mesh.quads.size());
  EXPECT_EQ(quality.back(), run.elementQuality.back());
  EXPECT_TRUE(dataArray(vtu, "metric").empty());
}

TEST(IoVtu, MeshioReadsIt) {
  const std::string py = vtuMeshioPython();
  if (py.empty()) GTEST_SKIP() << "python3-meshio not installed";
  const CaseRun run = runExample("point_source.json", true);
  const std::string path = testing::TempDir() + "/anisomesh_case.vtu", out = path + ".txt";
  writeTextFileAtomic(path, caseRunVtu(run));
  const std::string cmd = py +
                          " -c \"import meshio,sys; m=meshio.read(sys.argv[1]); "
                          "print(len(m.points), sum(len(c.data) for c in m.cells), m.point_data['metric'].shape[1], "
                          "len(m.cell_data['quality']))\" " +
                          path + " > " + out;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(out);
  size_t points = 0, cells = 0, components = 0, blocks = 0;
  in >> points >> cells >> components >> blocks;
  EXPECT_EQ(points, run.mesh.points.size());
  EXPECT_EQ(cells, run.mesh.edges.size() + run.mesh.triangles.size() + run.mesh.quads.size());
  EXPECT_EQ(components, 9u);
  EXPECT_GE(blocks, 2u);
}

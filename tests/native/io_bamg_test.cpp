// BAMG's own .mesh output (ffbamg) reads as a mesh: its extra sections (quoted Identifier
// and Geometry strings, VertexOnGeometricVertex, SubDomainFromMesh, ...) are skipped; a
// real ffbamg run is read back where ffbamg is installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/run_case.h"

using namespace anisomesh;

// The layout ffbamg 4.x writes (sections and their shapes as in a real run, fewer rows).
TEST(IoBamg, ReadsBamgOutputSkippingItsSections) {
  const std::string text =
      "MeshVersionFormatted 1\n\nDimension\n2\n\nIdentifier\n\"B=bg.mesh, G=cons from: bg.mesh;2, Date: 26/12/01\"\n\n"
      "Geometry\n\"bamg.mesh.gmsh\"\n\nVertices\n4\n0 0 1\n1 0 1\n1 1 1\n0 1 0\n\nEdges\n2\n1 2 1\n2 3 1\n\n"
      "Triangles\n2\n1 2 3 0\n1 3 4 0\n\nSubDomainFromMesh\n1\n3 1 1 0\n\nSubDomainFromGeom\n1\n2 66 1 0\n\n"
      "VertexOnGeometricVertex\n2\n 1 1\n 2 21\n\nVertexOnGeometricEdge\n1\n 3 1 0.999486307737\n\n"
      "EdgeOnGeometricEdge\n2\n1 1\n2 2\n\nMeshSupportOfVertices\n\n\"bg.mesh\"\n\n"
      "IdentityOfMeshSupport\n\";1, Date: 26/12/01 21:00 01s\"\n\nVertexOnSupportVertex\n1\n1 1\n\n"
      "VertexOnSupportEdge\n1\n3 1 0.5\n\nVertexOnSupportTriangle\n1\n4 2 0.1 0.2\n\nEnd\n";
  const Mesh m = parseMedit(text);
  EXPECT_EQ(m.dimension, 2);
  EXPECT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.edges.size(), 2u);
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.pointRefs, (std::vector<int>{1, 1, 1, 0}));
}

TEST(IoBamg, UnterminatedOrMissingStringsAndUnknownSectionsStillFail) {
  for (const char* text : {"MeshVersionFormatted 1\nDimension 2\nIdentifier\nnot-quoted\nEnd\n",
                           "MeshVersionFormatted 1\nDimension 2\nIdentifier\n\"never closed\nEnd\n",
                           "MeshVersionFormatted 1\nDimension 2\nBogusSection\n1\nEnd\n",
                           "MeshVersionFormatted 1\nDimension 2\nVertexOnGeometricVertex\n2\n1 1\nEnd\n"}) {
    try {
      parseMedit(text);
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::ParseError) << e.what();
    }
  }
}

TEST(IoBamg, ReadsARealFfbamgRun) {
  if (std::system("ffbamg -h >/dev/null 2>&1") == 127 || std::system("command -v ffbamg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffbamg (freefem) not installed";
  const std::string dir = testing::TempDir();
  const Mesh bg = runCase(readTextFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/point_source.json")).mesh;
  writeMeditFile(dir + "/bamg_bg.mesh", bg);
  std::string mtr = std::to_string(bg.vertexCount()) + " 1\n";
  for (int i = 0; i < bg.vertexCount(); ++i) mtr += "0.1\n";
  writeTextFileAtomic(dir + "/bamg_bg.mtr", mtr);
  const std::string cmd =
      "cd " + dir + " && ffbamg -b bamg_bg.mesh -M bamg_bg.mtr -o bamg_out.mesh -v 0 >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::string text = readTextFile(dir + "/bamg_out.mesh");
  ASSERT_NE(text.find("VertexOnGeometricVertex"), std::string::npos);
  const Mesh m = parseMedit(text);
  EXPECT_GT(m.triangles.size(), 100u);
  EXPECT_GT(m.edges.size(), 10u);
}

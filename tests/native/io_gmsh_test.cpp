// Gmsh .msh 4.1 and 2.2: write, read back, identical mesh (points bit for bit, elements,
// refs as physical tags), for planar meshes with quads and for a surface mesh; strict
// errors; and, where installed, meshio and gmsh read every written file.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/gmsh.h"
#include "anisomesh/io/mesh_formats.h"
#include "anisomesh/io/run_case.h"

using namespace anisomesh;

namespace {

Mesh gmshSampleMesh() {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0.5, 0), Vec3(0.1, 1e-17, 0)};
  m.pointRefs.assign(6, 0);
  m.edges = {{0, 1}, {1, 4}, {4, 2}};
  m.edgeRefs = {4, 7, 4};
  m.triangles = {{1, 4, 2}, {0, 5, 1}};
  m.triangleRefs = {3, 5};
  m.quads = {{0, 1, 2, 3}};
  m.quadRefs = {3};
  return m;
}

Mesh gmshCaseMesh(const std::string& example, bool quads) {
  RunCaseOptions o;
  o.quads = quads;
  return runCase(readTextFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + example), o).mesh;
}

// The same mesh up to element order within (dimension, ref) groups: compared as written.
void expectSameGmshMesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << i;
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.edgeRefs, b.edgeRefs);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangleRefs, b.triangleRefs);
  EXPECT_EQ(a.quads, b.quads);
  EXPECT_EQ(a.quadRefs, b.quadRefs);
}

// Elements reordered as the writer groups them (by ref, stable), for comparing.
Mesh grouped(Mesh m) {
  auto sortBy = [](auto& elements, std::vector<int>& refs) {
    std::vector<size_t> order(elements.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return refs[x] < refs[y]; });
    auto e = elements;
    auto r = refs;
    for (size_t i = 0; i < order.size(); ++i) {
      e[i] = elements[order[i]];
      r[i] = refs[order[i]];
    }
    elements = e;
    refs = r;
  };
  sortBy(m.edges, m.edgeRefs);
  sortBy(m.triangles, m.triangleRefs);
  sortBy(m.quads, m.quadRefs);
  return m;
}

void expectRoundTrip(const Mesh& m) {
  for (GmshVersion v : {GmshVersion::V41, GmshVersion::V22}) {
    const std::string text = writeGmsh(m, v);
    const Mesh back = parseGmsh(text);
    expectSameGmshMesh(grouped(m), back);
    EXPECT_EQ(writeGmsh(back, v), text) << "a second round trip changes the text";
  }
}

template <class F>
void expectGmshParseError(F f, const std::string& fragment) {
  try {
    f();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ParseError) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

bool haveCommand(const std::string& probe) { return std::system((probe + " >/dev/null 2>&1").c_str()) == 0; }

// A Python with meshio (Debian's python3-meshio is for /usr/bin/python3), or "".
std::string gmshMeshioPython() {
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (std::system((std::string(py) + " -c 'import meshio' >/dev/null 2>&1").c_str()) == 0) return py;
  return "";
}

}  // namespace

TEST(IoGmsh, SampleRoundTripsInBothVersions) {
  expectRoundTrip(gmshSampleMesh());
  const std::string v41 = writeGmsh(gmshSampleMesh());
  EXPECT_EQ(v41.rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n", 0), 0u) << v41;
  const std::string v22 = writeGmsh(gmshSampleMesh(), GmshVersion::V22);
  EXPECT_NE(v22.find("2 2 3 3 2 5 3\n"), std::string::npos) << v22;  // triangle, physical 3, elementary 3
}

TEST(IoGmsh, MeshedExamplesRoundTrip) {
  expectRoundTrip(gmshCaseMesh("point_source.json", false));
  expectRoundTrip(gmshCaseMesh("fig7_rect_holes_dr2.json", true));
  const Mesh surface = gmshCaseMesh("surface/surface_sphere.json", true);
  ASSERT_EQ(surface.dimension, 3);
  expectRoundTrip(surface);
}

TEST(IoGmsh, ReadsWhatGmshWritesAndSkipsUnknownSections) {
  // As gmsh 4 writes a square: point entities, a $PhysicalNames section, point elements.
  const std::string text =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 9 \"plate\"\n$EndPhysicalNames\n"
      "$Entities\n1 0 1 0\n1 0 0 0 0\n1 0 0 0 1 1 0 1 9 0\n$EndEntities\n"
      "$Nodes\n2 4 1 4\n0 1 0 1\n1\n0 0 0\n2 1 0 3\n2\n3\n4\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n"
      "$Elements\n2 3 1 3\n0 1 15 1\n1 1\n2 1 2 2\n2 1 2 3\n3 1 3 4\n$EndElements\n$Comments\nanything\n$EndComments\n";
  const Mesh m = parseGmsh(text);
  EXPECT_EQ(m.dimension, 2);
  ASSERT_EQ(m.points.size(), 4u);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangleRefs, (std::vector<int>{9, 9}));
  EXPECT_TRUE(m.edges.empty());
}

TEST(IoGmsh, StrictErrors) {
  expectGmshParseError([] { parseGmsh("$MeshFormat\n4.1 1 8\n$EndMeshFormat\n"); },
                       "binary .msh files are not supported");
  expectGmshParseError([] { parseGmsh("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n"); }, "expected version 4.1 or 2.2");
  expectGmshParseError(
      [] {
        parseGmsh(
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n"
            "$Elements\n1\n1 9 2 0 0 1 1 1 1 1 1\n$EndElements\n");
      },
      "element type 9 is not supported");
  expectGmshParseError(
      [] {
        parseGmsh(
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n"
            "$Elements\n1\n1 1 0 1 2\n$EndElements\n");
      },
      "a node tag defined in $Nodes");
  expectGmshParseError([] { parseGmsh("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n"); }, "msh line 6");
  expectGmshParseError([] { parseGmsh("mesh"); }, "'$MeshFormat'");
}

TEST(IoGmsh, MshExtensionDispatch) {
  EXPECT_EQ(meshFormatFromPath("a/b.MSH"), MeshFormat::Gmsh);
  const Mesh m = gmshSampleMesh();
  EXPECT_EQ(writeMeshString(m, MeshFormat::Gmsh), writeGmsh(m, GmshVersion::V41));
  EXPECT_EQ(writeMeshString(m, MeshFormat::Gmsh22), writeGmsh(m, GmshVersion::V22));
}

// meshio (python3-meshio) and gmsh read every file written: same counts; skipped when absent.
TEST(IoGmsh, MeshioAndGmshReadTheWrittenFiles) {
  const std::string py = gmshMeshioPython();
  const bool meshio = !py.empty();
  const bool gmsh = haveCommand("gmsh -version");
  if (!meshio && !gmsh) GTEST_SKIP() << "neither meshio (python3-meshio) nor gmsh is installed";
  const Mesh m = gmshCaseMesh("fig7_rect_holes_dr2.json", true);
  const std::string dir = testing::TempDir();
  for (GmshVersion v : {GmshVersion::V41, GmshVersion::V22}) {
    const std::string path = dir + (v == GmshVersion::V41 ? "/anisomesh_v41.msh" : "/anisomesh_v22.msh");
    writeTextFileAtomic(path, writeGmsh(m, v));
    if (meshio) {
      const std::string out = path + ".meshio.txt";
      const std::string cmd =
          py +
          " -c \"import meshio,sys,collections; m=meshio.read(sys.argv[1]); d=collections.Counter(); "
          "[d.update({c.type: len(c.data)}) for c in m.cells]; "
          "print(len(m.points), d.get('line',0), d.get('triangle',0), d.get('quad',0))\" " +
          path + " > " + out;
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
      std::ifstream in(out);
      size_t points = 0, lines = 0, triangles = 0, quads = 0;
      in >> points >> lines >> triangles >> quads;
      EXPECT_EQ(points, m.points.size()) << path;
      EXPECT_EQ(lines, m.edges.size()) << path;
      EXPECT_EQ(triangles, m.triangles.size()) << path;
      EXPECT_EQ(quads, m.quads.size()) << path;
    }
    if (gmsh) {
      // gmsh re-saves the file as 2.2; reading that back gives the same element counts.
      const std::string out = path + ".gmsh.msh";
      const std::string cmd = "gmsh " + path + " -0 -save_all -format msh22 -o " + out + " >/dev/null 2>&1";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
      const Mesh back = parseGmsh(readTextFile(out));
      EXPECT_EQ(back.points.size(), m.points.size()) << path;
      EXPECT_EQ(back.triangles.size(), m.triangles.size()) << path;
      EXPECT_EQ(back.quads.size(), m.quads.size()) << path;
      EXPECT_EQ(back.edges.size(), m.edges.size()) << path;
    }
  }
}

#include <gtest/gtest.h>

#include "anisomesh/core/error.h"
#include "anisomesh/io/mesh_formats.h"

using namespace anisomesh;

namespace {

Mesh sampleMesh() {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0.5, 0)};
  m.pointRefs.assign(5, 0);
  m.edges = {{0, 1}};
  m.edgeRefs = {4};
  m.triangles = {{1, 4, 2}};
  m.triangleRefs = {3};
  m.quads = {{0, 1, 2, 3}};
  m.quadRefs = {6};
  return m;
}

template <class F>
void expectParseError(F f, const std::string& fragment) {
  try {
    f();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ParseError) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(IoVtk, RoundTripWithRefs) {
  const Mesh m = sampleMesh();
  const std::string text = writeVtk(m);
  EXPECT_NE(text.find("DATASET UNSTRUCTURED_GRID"), std::string::npos);
  EXPECT_NE(text.find("SCALARS ref int 1"), std::string::npos);
  const Mesh b = parseVtk(text);
  EXPECT_EQ(b.dimension, 2);
  EXPECT_EQ(b.points, m.points);
  EXPECT_EQ(b.edges, m.edges);
  EXPECT_EQ(b.edgeRefs, m.edgeRefs);
  EXPECT_EQ(b.triangles, m.triangles);
  EXPECT_EQ(b.triangleRefs, m.triangleRefs);
  EXPECT_EQ(b.quads, m.quads);
  EXPECT_EQ(b.quadRefs, m.quadRefs);
}

TEST(IoVtk, Errors) {
  expectParseError([] { parseVtk("hello\n"); }, "VTK line 1");
  const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 double\n0 0 0\n";
  expectParseError([&] { parseVtk(head + "CELLS 1 4\n3 0 0 1\nCELL_TYPES 1\n5\n"); },
                   "line 8: vertex index 1 of cell 0 is out of range");
  expectParseError([&] { parseVtk(head + "CELLS 1 2\n1 0\nCELL_TYPES 1\n1\n"); }, "unsupported VTK type 1");
  expectParseError([] { parseVtk("# vtk DataFile Version 3.0\nt\nBINARY\n"); }, "line 3: expected 'ASCII'");
}

TEST(IoObj, RoundTrip) {
  const Mesh m = sampleMesh();
  const Mesh b = parseObj(writeObj(m));
  EXPECT_EQ(b.dimension, 2);
  EXPECT_EQ(b.points, m.points);
  EXPECT_EQ(b.edges, m.edges);
  EXPECT_EQ(b.triangles, m.triangles);
  EXPECT_EQ(b.quads, m.quads);
}

TEST(IoObj, IndexFormsAndErrors) {
  const Mesh m = parseObj("# c\nv 0 0 1\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 -1//1\n");
  EXPECT_EQ(m.dimension, 3);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{0, 1, 2}));
  expectParseError([] { parseObj("v 0 0 0\nv 1 0 0\nf 1 2 9\n"); }, "OBJ line 3: vertex index 9 is out of range 1..2");
  expectParseError([] { parseObj("v 0 zero 0\n"); }, "OBJ line 1: expected coordinate y of a vertex, got 'zero'");
  expectParseError([] { parseObj("v 0 0 0\nf 1 1\n"); }, "OBJ line 2: expected a face with 3 or 4 vertices");
}

TEST(IoFormats, DispatchByExtension) {
  EXPECT_EQ(meshFormatFromPath("x.mesh"), MeshFormat::Medit);
  EXPECT_EQ(meshFormatFromPath("x.VTK"), MeshFormat::Vtk);
  EXPECT_EQ(meshFormatFromPath("x.obj"), MeshFormat::Obj);
  try {
    meshFormatFromPath("x.stl");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
    EXPECT_NE(std::string(e.what()).find(".mesh, .meshb, .vtk, .obj or .msh"), std::string::npos);
  }
  const Mesh m = sampleMesh();
  for (MeshFormat f : {MeshFormat::Medit, MeshFormat::Vtk, MeshFormat::Obj})
    EXPECT_EQ(parseMeshString(writeMeshString(m, f), f).triangles, m.triangles);
}

// Binary Medit .meshb / .solb: write, read back, identical mesh; the same mesh as the text
// .mesh; files of every version (1-4) and both byte orders read; meshio reads what we write
// and we read what meshio writes (where python3-meshio is installed); truncated and lying
// files are coded ParseErrors naming the keyword and the byte offset; the CLI by extension.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/medit_binary.h"
#include "anisomesh/io/mesh_formats.h"
#include "anisomesh/io/run_case.h"
#include "cli_test_util.h"

using namespace anisomesh;

namespace {

Mesh meshbSampleMesh() {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0.5, 0), Vec3(0.1, 1e-17, 0)};
  m.pointRefs = {1, 0, 0, 2, 0, -3};
  m.edges = {{0, 1}, {1, 4}, {4, 2}};
  m.edgeRefs = {4, 7, 4};
  m.triangles = {{1, 4, 2}, {0, 5, 1}};
  m.triangleRefs = {3, 5};
  m.quads = {{0, 1, 2, 3}};
  m.quadRefs = {-2147483647 - 1};
  return m;
}

Mesh meshbCaseMesh(const std::string& example, bool quads) {
  RunCaseOptions o;
  o.quads = quads;
  return runCase(readTextFile(std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + example), o).mesh;
}

void expectSameMeshb(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << i;
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.pointRefs, b.pointRefs);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.edgeRefs, b.edgeRefs);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangleRefs, b.triangleRefs);
  EXPECT_EQ(a.quads, b.quads);
  EXPECT_EQ(a.quadRefs, b.quadRefs);
}

template <class F>
void expectMeshbParseError(F f, const std::string& fragment) {
  try {
    f();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ParseError) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// An independent libMeshb encoder for the tests: any version, either byte order.
struct Encoder {
  int version;
  bool bigEndian;
  std::string out;
  void put(std::uint64_t v, size_t n) {
    for (size_t k = 0; k < n; ++k) {
      const size_t shift = bigEndian ? 8 * (n - 1 - k) : 8 * k;
      out.push_back(char((v >> shift) & 0xff));
    }
  }
  void word(std::int64_t v) { put(std::uint64_t(v), 4); }
  void integer(std::int64_t v) { put(std::uint64_t(v), version >= 4 ? 8 : 4); }
  void real(double d) {
    if (version == 1) {
      const float f = float(d);
      std::uint32_t u;
      std::memcpy(&u, &f, 4);
      put(u, 4);
    } else {
      std::uint64_t u;
      std::memcpy(&u, &d, 8);
      put(u, 8);
    }
  }
  size_t positionBytes() const { return version >= 3 ? 8 : 4; }
  // A keyword whose next-keyword position is patched by end().
  size_t keyword(int code) {
    word(code);
    const size_t at = out.size();
    put(0, positionBytes());
    return at;
  }
  void end(size_t at) {
    Encoder patch{version, bigEndian, ""};
    patch.put(out.size(), positionBytes());
    out.replace(at, positionBytes(), patch.out);
  }
};

// The sample mesh (with Corners, Ridges, RequiredVertices and an unknown keyword) in a
// given version and byte order.
std::string encodedSample(int version, bool bigEndian) {
  const Mesh m = meshbSampleMesh();
  Encoder e{version, bigEndian, ""};
  e.word(1);
  e.word(version);
  size_t k = e.keyword(3);
  e.word(2);
  e.end(k);
  k = e.keyword(4);
  e.integer(std::int64_t(m.points.size()));
  for (size_t i = 0; i < m.points.size(); ++i) {
    e.real(m.points[i].x());
    e.real(m.points[i].y());
    e.integer(m.pointRefs[i]);
  }
  e.end(k);
  k = e.keyword(13);  // Corners
  e.integer(2);
  e.integer(1);
  e.integer(4);
  e.end(k);
  k = e.keyword(5);
  e.integer(std::int64_t(m.edges.size()));
  for (size_t i = 0; i < m.edges.size(); ++i) {
    for (int v : m.edges[i]) e.integer(v + 1);
    e.integer(m.edgeRefs[i]);
  }
  e.end(k);
  k = e.keyword(14);  // Ridges
  e.integer(1);
  e.integer(2);
  e.end(k);
  k = e.keyword(20);  // NormalAtVertices: skipped by its position
  e.integer(1);
  e.integer(1);
  e.integer(1);
  e.end(k);
  k = e.keyword(6);
  e.integer(std::int64_t(m.triangles.size()));
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    for (int v : m.triangles[i]) e.integer(v + 1);
    e.integer(m.triangleRefs[i]);
  }
  e.end(k);
  k = e.keyword(15);  // RequiredVertices
  e.integer(1);
  e.integer(3);
  e.end(k);
  k = e.keyword(7);
  e.integer(std::int64_t(m.quads.size()));
  for (size_t i = 0; i < m.quads.size(); ++i) {
    for (int v : m.quads[i]) e.integer(v + 1);
    e.integer(m.quadRefs[i]);
  }
  e.end(k);
  e.word(54);
  e.put(0, e.positionBytes());
  return e.out;
}

// A Python with meshio, or "".
std::string meshbMeshioPython() {
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (std::system((std::string(py) + " -c 'import meshio' >/dev/null 2>&1").c_str()) == 0) return py;
  return "";
}

}  // namespace

TEST(IoMeshb, SampleRoundTripsIdentically) {
  const Mesh m = meshbSampleMesh();
  const std::string bytes = writeMeditBinary(m);
  // Code 1, version 2, Dimension (3) whose next keyword is at byte 20, dimension 2.
  const unsigned char head[] = {1, 0, 0, 0, 2, 0, 0, 0, 3, 0, 0, 0, 20, 0, 0, 0, 2, 0, 0, 0};
  ASSERT_GE(bytes.size(), sizeof head);
  EXPECT_EQ(std::memcmp(bytes.data(), head, sizeof head), 0);
  const Mesh back = parseMeditBinary(bytes);
  expectSameMeshb(m, back);
  EXPECT_EQ(writeMeditBinary(back), bytes) << "a second round trip changes the bytes";
  EXPECT_EQ(writeMeshString(m, MeshFormat::MeditBinary), bytes);
  EXPECT_EQ(meshFormatFromPath("a/b.MESHB"), MeshFormat::MeditBinary);
}

TEST(IoMeshb, MeshedExamplesRoundTripAndMatchTheTextFormat) {
  for (const auto& [example, quads] : {std::pair<const char*, bool>{"point_source.json", false},
                                       {"fig7_rect_holes_dr2.json", true},
                                       {"surface/surface_sphere.json", true}}) {
    const Mesh m = meshbCaseMesh(example, quads);
    const Mesh binary = parseMeditBinary(writeMeditBinary(m));
    const Mesh text = parseMedit(writeMedit(m));
    expectSameMeshb(text, binary);
    EXPECT_EQ(writeMedit(binary), writeMedit(m)) << example;
  }
}

TEST(IoMeshb, ReadsEveryVersionInBothByteOrders) {
  const Mesh m = meshbSampleMesh();
  for (int version = 1; version <= 4; ++version)
    for (bool big : {false, true}) {
      SCOPED_TRACE("version " + std::to_string(version) + (big ? " big-endian" : " little-endian"));
      const Mesh back = parseMeditBinary(encodedSample(version, big));
      if (version == 1) {  // float coordinates
        ASSERT_EQ(back.points.size(), m.points.size());
        for (size_t i = 0; i < m.points.size(); ++i)
          EXPECT_EQ(back.points[i], m.points[i].cast<float>().cast<double>()) << i;
        EXPECT_EQ(back.triangles, m.triangles);
        EXPECT_EQ(back.quadRefs, m.quadRefs);
      } else {
        expectSameMeshb(m, back);
      }
    }
}

TEST(IoMeshb, TruncatedFilesAreParseErrorsAtEveryLength) {
  const std::string bytes = writeMeditBinary(meshbSampleMesh());
  // Cut anywhere but where End's position word would start (writers may leave it out).
  expectSameMeshb(meshbSampleMesh(), parseMeditBinary(bytes.substr(0, bytes.size() - 4)));
  for (size_t n = 0; n < bytes.size(); ++n) {
    if (n == bytes.size() - 4) continue;
    try {
      parseMeditBinary(bytes.substr(0, n));
      ADD_FAILURE() << "a file cut at byte " << n << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::ParseError) << n << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("Medit binary mesh, byte "), std::string::npos) << e.what();
    }
  }
  const std::string sol = writeSolBinary(metricsToSol({Metric::isotropic(0.5), Metric::isotropic(2)}));
  for (size_t n = 0; n < sol.size(); ++n)
    if (n != sol.size() - 4) {
      EXPECT_THROW(parseSolBinary(sol.substr(0, n)), Error) << n;
    }
}

TEST(IoMeshb, LyingCountsIndicesAndReferencesAreNamed) {
  std::string bytes = writeMeditBinary(meshbSampleMesh());
  // Vertices at byte 20: code, position, count (byte 28).
  std::string lying = bytes;
  lying[28] = char(0xff), lying[29] = char(0xff), lying[30] = char(0xff), lying[31] = char(0x7f);
  expectMeshbParseError([&] { parseMeditBinary(lying); }, "byte 28 (Vertices): 2147483647 vertices need 20 bytes each");
  // The first edge's first vertex: past the 6 vertices of 20 bytes.
  const size_t edges = 32 + 6 * 20;
  std::string index = bytes;
  index[edges + 12] = 9;
  expectMeshbParseError([&] { parseMeditBinary(index); }, "(Edges): vertex index 9 of Edges 1 is out of range 1..6");
  expectMeshbParseError([&] { parseMeditBinary(bytes.substr(0, bytes.size() - 8)); }, "expected the End keyword");
  expectMeshbParseError([&] { parseMeditBinary(writeMedit(meshbSampleMesh())); }, "byte 0: expected the code 1");
  std::string dim = bytes;
  dim[16] = 4;
  expectMeshbParseError([&] { parseMeditBinary(dim); }, "byte 16 (Dimension): expected Dimension 2 or 3, got 4");
  std::string version = bytes;
  version[4] = 5;
  expectMeshbParseError([&] { parseMeditBinary(version); }, "byte 4: unsupported version 5");
  // Version 4: a 64-bit reference beyond 32 bits; an unknown keyword whose position points back.
  std::string v4 = encodedSample(4, false);
  const size_t ref1 = 8 + 16 + 20 + 16;  // header, Dimension, Vertices head, x y of vertex 1
  ASSERT_EQ(v4[ref1], 1);
  v4[ref1 + 5] = 1;
  expectMeshbParseError([&] { parseMeditBinary(v4); },
                        "the reference 1099511627777 of vertex 1 does not fit in 32 bits");
  Encoder e{2, false, ""};
  e.word(1), e.word(2), e.word(3), e.word(20), e.word(2), e.word(99), e.word(4);
  expectMeshbParseError([&] { parseMeditBinary(e.out); }, "byte 24 (keyword 99): the position of the next keyword, 4");
}

TEST(IoMeshb, SolutionsRoundTripInEveryType) {
  for (int type = 1; type <= 3; ++type)
    for (int dimension = 2; dimension <= 3; ++dimension) {
      SolData sol;
      sol.type = type;
      sol.dimension = dimension;
      for (int i = 0; i < 4 * sol.valuesPerVertex(); ++i) sol.values.push_back(0.1 * i + 1e-300);
      const std::string bytes = writeSolBinary(sol);
      const SolData back = parseSolBinary(bytes);
      EXPECT_EQ(back.type, type);
      EXPECT_EQ(back.dimension, dimension);
      EXPECT_EQ(back.values, sol.values);
      EXPECT_EQ(back.count(), 4);
      EXPECT_EQ(parseSol(writeSol(sol)).values, sol.values) << "the text format holds the same";
    }
  SolData tensor = metricsToSol({Metric::fromTensor(4, 1, 9), Metric::isotropic(0.25)});
  std::string lying = writeSolBinary(tensor);
  lying[28] = 100;  // the vertex count
  expectMeshbParseError([&] { parseSolBinary(lying); }, "byte 28 (SolAtVertices): 100 solution values of 24 bytes");
  std::string type = writeSolBinary(tensor);
  type[36] = 4;
  expectMeshbParseError([&] { parseSolBinary(type); }, "expected solution type 1 (scalar), 2 (vector) or 3");
  SolData vector;
  vector.type = 2;
  vector.values = {1, 2};
  try {
    solToMetrics(vector, 1);
    FAIL() << "a vector solution drove a metric";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
  }
  const std::string path = clitest::tmp("m.solb");
  writeSolFile(path, tensor);
  EXPECT_EQ(readTextFile(path), writeSolBinary(tensor));
  EXPECT_EQ(readSolFile(path).values, tensor.values);
}

// meshio reads our .meshb (counts, coordinates, refs) and we read the .meshb meshio writes
// (version 3); skipped when python3-meshio is absent.
TEST(IoMeshb, MeshioReadsAndWritesTheBinaryFormat) {
  const std::string py = meshbMeshioPython();
  if (py.empty()) GTEST_SKIP() << "meshio (python3-meshio) is not installed";
  const Mesh m = meshbCaseMesh("fig7_rect_holes_dr2.json", true);
  const std::string ours = clitest::tmp("ours.meshb"), theirs = clitest::tmp("theirs.meshb");
  const std::string report = clitest::tmp("meshio.txt");
  writeMeshFile(ours, m);
  const std::string cmd =
      py +
      " -c \"import meshio,sys,collections; m=meshio.read(sys.argv[1]); d=collections.Counter(); "
      "[d.update({c.type: len(c.data)}) for c in m.cells]; "
      "print(len(m.points), d.get('line',0), d.get('triangle',0), d.get('quad',0), repr(float(m.points[-1][0])), "
      "int(m.cell_data['medit:ref'][-1][-1])); meshio.write(sys.argv[2], m)\" " +
      ours + " " + theirs + " > " + report + " 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(report);
  size_t points = 0, lines = 0, triangles = 0, quads = 0;
  double lastX = 0;
  int lastRef = 0;
  in >> points >> lines >> triangles >> quads >> lastX >> lastRef;
  EXPECT_EQ(points, m.points.size());
  EXPECT_EQ(lines, m.edges.size());
  EXPECT_EQ(triangles, m.triangles.size());
  EXPECT_EQ(quads, m.quads.size());
  EXPECT_EQ(lastX, m.points.back().x());
  EXPECT_EQ(lastRef, m.quadRefs.back());
  const std::string back = readTextFile(theirs);
  ASSERT_GE(back.size(), 8u);
  EXPECT_EQ(back[4], 3) << "meshio writes version 3";
  expectSameMeshb(m, readMeshFile(theirs));
}

// The CLI reads and writes .meshb / .solb by extension: remesh from .meshb + .solb gives
// the bytes it gives from .mesh + .sol; adapt writes the fields as .solb beside a .meshb.
TEST(IoMeshb, CliUsesTheBinaryFormatsByExtension) {
  const std::string mesh = std::string(ANISOMESH_SOURCE_DIR) + "/tests/bad_input/square.mesh";
  const std::string sol = std::string(ANISOMESH_SOURCE_DIR) + "/tests/bad_input/square.sol";
  const std::string meshb = clitest::tmp("in.meshb"), solb = clitest::tmp("in.solb");
  writeMeshFile(meshb, readMeshFile(mesh));
  writeSolFile(solb, readSolFile(sol));
  const std::string a = clitest::tmp("a.mesh"), b = clitest::tmp("b.mesh"), c = clitest::tmp("c.meshb");
  ASSERT_EQ(clitest::run("remesh " + mesh + " -sol " + sol + " -o " + a).code, 0);
  const clitest::CliRun rb = clitest::run("remesh " + meshb + " -sol " + solb + " -o " + b);
  ASSERT_EQ(rb.code, 0) << rb.err;
  EXPECT_EQ(clitest::slurp(a), clitest::slurp(b));
  ASSERT_EQ(clitest::run("remesh " + meshb + " -sol " + solb + " -o " + c).code, 0);
  expectSameMeshb(readMeshFile(a), readMeshFile(c));
  const std::string adapted = clitest::tmp("adapted.meshb"), square = clitest::tmp("square.meshb");
  writeMeshFile(square, readMeshFile(clitest::example("adaptation/square.mesh")));
  const clitest::CliRun ad = clitest::run("adapt " + square + " -field 'x*x' -nv 200 -iterations 1 -o " + adapted);
  ASSERT_EQ(ad.code, 0) << ad.err;
  const Mesh out = readMeshFile(adapted);
  const SolData field = readSolFile(clitest::tmp("adapted.solb"));
  EXPECT_EQ(field.count(), out.vertexCount());
  std::string broken = readTextFile(meshb);
  broken.resize(broken.size() - 3);
  writeTextFileAtomic(meshb, broken);
  const clitest::CliRun bad = clitest::run("remesh " + meshb + " -sol " + solb + " -o " + b);
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("PARSE_ERROR"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("Medit binary mesh, byte"), std::string::npos) << bad.err;
}

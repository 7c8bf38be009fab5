#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "../../native/src/io/tokens.h"  // the private tokenizer's newline count
#include "anisomesh/core/error.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/medit.h"

using namespace anisomesh;

namespace {

Mesh meditSampleMesh(int dimension) {
  Mesh m;
  m.dimension = dimension;
  const double z = dimension == 3 ? 0.25 : 0.0;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, z), Vec3(1, 1, 0), Vec3(0, 1, z), Vec3(2, 0.5, 0), Vec3(0.1, 1.0 / 3.0, 0)};
  m.pointRefs = {1, 2, 3, 4, 5, 0};
  m.edges = {{0, 1}, {1, 4}};
  m.edgeRefs = {7, 8};
  m.triangles = {{1, 4, 2}, {0, 1, 5}};
  m.triangleRefs = {3, 9};
  m.quads = {{0, 1, 2, 3}};
  m.quadRefs = {11};
  return m;
}

void expectSameMesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.dimension, b.dimension);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]) << i;  // exact round trip
  EXPECT_EQ(a.pointRefs, b.pointRefs);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.edgeRefs, b.edgeRefs);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangleRefs, b.triangleRefs);
  EXPECT_EQ(a.quads, b.quads);
  EXPECT_EQ(a.quadRefs, b.quadRefs);
}

// Parses text and checks the error code and a message fragment.
template <class F>
void expectMeditError(F f, ErrorCode code, const std::string& fragment) {
  try {
    f();
    FAIL() << "no error, expected " << errorCodeName(code);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

std::string tempPath(const std::string& name) { return ::testing::TempDir() + "anisomesh_io_" + name; }

bool fileExists(const std::string& path) { return std::ifstream(path).good(); }

}  // namespace

TEST(IoMedit, RoundTrip2D) {
  const Mesh m = meditSampleMesh(2);
  const std::string text = writeMedit(m);
  EXPECT_NE(text.find("Dimension 2"), std::string::npos);
  EXPECT_NE(text.find("Quadrilaterals"), std::string::npos);
  expectSameMesh(m, parseMedit(text));
}

TEST(IoMedit, RoundTrip3D) {
  const Mesh m = meditSampleMesh(3);
  expectSameMesh(m, parseMedit(writeMedit(m)));
}

// Files are parsed as they are read (a memory map, the parsed batches of lines given
// back): the same mesh and solution as from the whole text, also when a section's last
// line holds a comment or its last record is split over two lines (its fast reading fails
// after earlier batches were given back and the section is read again token by token).
TEST(IoMedit, FileReadInBatchesGivesTheWholeTextsMesh) {
  Mesh m;
  const int n = 560;  // 313,600 vertices, 623,538 triangles: batches of 262,144 lines
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.points.push_back(Vec3(i / 7.0, j / 3.0 + 1e-9 * i, 0));
  m.pointRefs.assign(m.points.size(), 2);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      m.triangles.push_back({a, a + 1, a + n + 1});
      m.triangles.push_back({a, a + n + 1, a + n});
      m.triangleRefs.insert(m.triangleRefs.end(), {i % 5, j % 3});
    }
  m.dimension = 2;
  std::string text = writeMedit(m);
  const std::string path = tempPath("batches.mesh");
  auto write = [&](const std::string& t) { std::ofstream(path, std::ios::binary) << t; };
  write(text);
  expectSameMesh(m, readMeditFile(path));
  const size_t end = text.rfind("\nEnd");
  ASSERT_NE(end, std::string::npos);
  text.insert(end, " # the last triangle");            // the last line of the Triangles section
  const size_t lastRef = text.rfind(" 2\nTriangles");  // the last vertex's reference on a line of its own
  ASSERT_NE(lastRef, std::string::npos);
  text[lastRef] = '\n';
  write(text);
  expectSameMesh(m, readMeditFile(path));
  SolData sol;
  sol.dimension = 2;
  sol.type = 3;
  for (size_t k = 0; k < m.points.size(); ++k) sol.values.insert(sol.values.end(), {1.0 + k, 0.5 / (k + 1), 3.0});
  std::string solText = writeSol(sol);
  const std::string solPath = tempPath("batches.sol");
  std::ofstream(solPath, std::ios::binary) << solText;
  EXPECT_EQ(readSolFile(solPath).values, sol.values);
  const size_t lastValue = solText.rfind(" 3\n\nEnd");  // the last vertex's last value on a line of its own
  ASSERT_NE(lastValue, std::string::npos);
  solText[lastValue] = '\n';
  std::ofstream(solPath, std::ios::binary) << solText;
  EXPECT_EQ(readSolFile(solPath).values, sol.values);
  std::remove(path.c_str());
  std::remove(solPath.c_str());
}

TEST(IoMedit, FileRoundTripIsAtomic) {
  const std::string path = tempPath("round.mesh");
  writeMeditFile(path, meditSampleMesh(2));
  expectSameMesh(meditSampleMesh(2), readMeditFile(path));
  std::remove(path.c_str());
}

TEST(IoMedit, ParsesVersion1CommentsAndSkippedSections) {
  const std::string text =
      "# a comment\n"
      "MeshVersionFormatted 1 # trailing comment\n"
      "Dimension\n3\n"
      "Vertices\n3\n0 0 0 1\n1 0 0 1\n0 1 0 2\n"
      "Corners\n1\n1\n"
      "Triangles\n1\n1 2 3 4\n"
      "End\n";
  const Mesh m = parseMedit(text);
  EXPECT_EQ(m.dimension, 3);
  EXPECT_EQ(m.vertexCount(), 3);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangleRefs[0], 4);
}

TEST(IoMedit, MalformedFilesNameLineAndExpectation) {
  const std::string head = "MeshVersionFormatted 2\nDimension 2\n";
  expectMeditError([&] { parseMedit(head + "Vertices\n2\n0 0 0\n1 x 0\nEnd\n"); }, ErrorCode::ParseError,
                   "line 6: expected coordinate y of vertex 2, got 'x'");
  expectMeditError([&] { parseMedit(head + "Vertices\n2\n0 0 0\n1 1 0\nTriangles\n1\n1 2 3 0\n"); },
                   ErrorCode::ParseError, "line 9: vertex index 3 of Triangles 1 is out of range 1..2");
  expectMeditError([&] { parseMedit(head + "Vertices\n3\n0 0 0\n"); }, ErrorCode::ParseError, "larger than the data");
  expectMeditError([&] { parseMedit(head + "Vertices\n1\n0 0\n"); }, ErrorCode::ParseError,
                   "expected the reference of vertex 1, got end of file");
  expectMeditError([&] { parseMedit(head + "Vertex\n1\n0 0 0\n"); }, ErrorCode::ParseError,
                   "line 3: expected a Medit keyword");
  expectMeditError([&] { parseMedit("MeshVersionFormatted 2\nDimension 4\n"); }, ErrorCode::ParseError,
                   "line 2: expected Dimension 2 or 3");
  expectMeditError([&] { parseMedit("Dimension 2\nVertices\n0\n"); }, ErrorCode::ParseError,
                   "expected MeshVersionFormatted before Vertices");
  expectMeditError([&] { parseMedit(head + "Triangles\n0\n"); }, ErrorCode::ParseError,
                   "expected Vertices before Triangles");
  expectMeditError([&] { parseMedit(head + "Vertices\n-1\n"); }, ErrorCode::ParseError, "nonnegative");
  // Keywords are case-sensitive, as in Medit.
  expectMeditError([&] { parseMedit(head + "vertices\n0\n"); }, ErrorCode::ParseError, "got 'vertices'");
}

TEST(IoMedit, UnreadableFileIsIoError) {
  expectMeditError([] { readMeditFile("/nonexistent/dir/x.mesh"); }, ErrorCode::IoError, "/nonexistent/dir/x.mesh");
}

TEST(IoSol, ScalarAndTensorRoundTrip) {
  SolData s;
  s.type = 1;
  s.values = {0.1, 0.25, 1.0 / 3.0};
  const SolData back = parseSol(writeSol(s));
  EXPECT_EQ(back.type, 1);
  EXPECT_EQ(back.dimension, 2);
  EXPECT_EQ(back.values, s.values);
  const std::vector<Metric> metrics{Metric::fromSizes(0.3, 0.01, 0.5), Metric::isotropic(2.0)};
  const SolData t = metricsToSol(metrics);
  const SolData tb = parseSol(writeSol(t));
  EXPECT_EQ(tb.type, 3);
  EXPECT_EQ(tb.values, t.values);
  const std::vector<Metric> mb = solToMetrics(tb, 2);
  for (size_t i = 0; i < 2; ++i)
    EXPECT_LT((mb[i].tensor() - metrics[i].tensor()).norm(), 1e-9 * metrics[i].tensor().norm());
}

TEST(IoSol, ScalarIsIsotropicSize) {
  SolData s;
  s.values = {0.5};
  const auto m = solToMetrics(s, 1);
  EXPECT_NEAR(m[0].sizeAlong(Vec2(1, 0)), 0.5, 1e-14);
  EXPECT_NEAR(m[0].sizeAlong(Vec2(1, 1)), 0.5, 1e-14);
}

TEST(IoSol, FileRoundTrip) {
  const std::string path = tempPath("round.sol");
  SolData s;
  s.type = 3;
  s.values = {4, 0, 1, 2, 0.5, 3};
  writeSolFile(path, s);
  EXPECT_EQ(readSolFile(path).values, s.values);
  std::remove(path.c_str());
}

TEST(IoSol, Errors) {
  const std::string head = "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n2\n";
  expectMeditError([&] { parseSol(head + "1 4\n1 1\n2 2\nEnd\n"); }, ErrorCode::ParseError,
                   "line 5: expected solution type 1 (scalar), 2 (vector) or 3 (symmetric tensor), got 4");
  expectMeditError([&] { parseSol(head + "2 1 1\n1 1\n"); }, ErrorCode::ParseError,
                   "line 5: expected 1 solution field, got 2");
  expectMeditError([&] { parseSol(head + "1 3\n1 0 1\n1 0 oops\n"); }, ErrorCode::ParseError,
                   "line 7: expected value 3 of vertex 2, got 'oops'");
  expectMeditError([&] { parseSol("MeshVersionFormatted 2\nDimension 2\nEnd\n"); }, ErrorCode::ParseError,
                   "expected a SolAtVertices section");
  SolData s;
  s.values = {1, 2, 3};
  expectMeditError([&] { solToMetrics(s, 5); }, ErrorCode::ParseError,
                   "the solution has 3 values but the mesh has 5 vertices");
  s.values = {1, -2, 3};
  expectMeditError([&] { solToMetrics(s, 3); }, ErrorCode::InvalidMetric, "vertex 2");
  expectMeditError([] { readSolFile("/nonexistent/x.sol"); }, ErrorCode::IoError, "cannot open");
}

TEST(IoFile, AtomicWriteLeavesNoFileOnFailure) {
  // The folder does not exist: nothing may be created, neither the file nor a temporary.
  const std::string path = tempPath("missing_dir/out.mesh");
  expectMeditError([&] { writeTextFileAtomic(path, "data"); }, ErrorCode::IoError, "out.mesh");
  EXPECT_FALSE(fileExists(path));
  // A failure while producing the contents never reaches the file.
  const std::string path2 = tempPath("never.mesh");
  std::remove(path2.c_str());
  Mesh bad;
  bad.dimension = 5;
  EXPECT_THROW(writeMeditFile(path2, bad), Error);
  EXPECT_FALSE(fileExists(path2));
}

TEST(IoFile, AtomicWriteReplacesExistingFile) {
  const std::string path = tempPath("replace.txt");
  writeTextFileAtomic(path, "first");
  writeTextFileAtomic(path, "second");
  EXPECT_EQ(readTextFile(path), "second");
  std::remove(path.c_str());
}

TEST(IoFile, Extension) {
  EXPECT_EQ(fileExtension("a/b.MESH"), "mesh");
  EXPECT_EQ(fileExtension("a.b/c"), "");
  EXPECT_EQ(fileExtension("out.vtk"), "vtk");
}

TEST(IoFile, ReadingADirectoryIsIoError) {
  expectMeditError([] { readTextFile(::testing::TempDir()); }, ErrorCode::IoError, "");
}

// Issue #15: numbers that do not fit are refused with the line, never changed silently.
TEST(IoMedit, StrictNumbersAndReferences) {
  const std::string head = "MeshVersionFormatted 2\nDimension 2\n";
  expectMeditError([&] { parseMedit(head + "Vertices\n1\n1e999 0 0\nEnd\n"); }, ErrorCode::ParseError,
                   "line 5: coordinate x of vertex 1 '1e999' overflows a double");
  expectMeditError([&] { parseMedit(head + "Vertices\n1\n0 -1e400 0\nEnd\n"); }, ErrorCode::ParseError,
                   "line 5: coordinate y of vertex 1 '-1e400' overflows a double");
  expectMeditError([&] { parseMedit(head + "Vertices\n1\n0 0 99999999999\nEnd\n"); }, ErrorCode::ParseError,
                   "line 5: the reference of vertex 1 99999999999 does not fit in a 32-bit integer");
  expectMeditError([&] { parseMedit(head + "Vertices\n3\n0 0 0\n1 0 0\n0 1 0\nTriangles\n1\n1 2 3\n-99999999999\n"); },
                   ErrorCode::ParseError,
                   "line 11: the reference of Triangles 1 -99999999999 does not fit in a 32-bit");
  expectMeditError([&] { parseMedit(head + "Vertices\n1\n0 0 99999999999999999999\n"); }, ErrorCode::ParseError,
                   "line 5: the reference of vertex 1 '99999999999999999999' does not fit in a 64-bit integer");
  // The largest references that fit, and an underflow (the nearest double, as strtod).
  const Mesh m = parseMedit(head + "Vertices\n2\n1e-400 0 2147483647\n+0.5 0x1p-2 -2147483648\nEnd\n");
  EXPECT_EQ(m.pointRefs, (std::vector<int>{2147483647, -2147483648}));
  EXPECT_EQ(m.points[0].x(), 0.0);
  EXPECT_EQ(m.points[1].x(), 0.5);   // '+' sign (strtod's syntax kept)
  EXPECT_EQ(m.points[1].y(), 0.25);  // hexadecimal (strtod's syntax kept)
  expectMeditError([&] { parseSol(head + "SolAtVertices\n1\n1 1\n1e999\nEnd\n"); }, ErrorCode::ParseError,
                   "line 6: value 1 of vertex 1 '1e999' overflows a double");
}

// Issue #15: Dimension appears once, before the data (a late one would reinterpret it).
TEST(IoMedit, DimensionOnceBeforeTheData) {
  expectMeditError([] { parseMedit("MeshVersionFormatted 2\nDimension 2\nDimension 3\nVertices\n0\nEnd\n"); },
                   ErrorCode::ParseError, "Dimension appears twice");
  expectMeditError([] { parseMedit("MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 1 0\nDimension 2\nEnd\n"); },
                   ErrorCode::ParseError, "Dimension after the data");
  expectMeditError([] { parseSol("MeshVersionFormatted 2\nDimension 2\nDimension 2\nSolAtVertices\n0\n1 1\nEnd\n"); },
                   ErrorCode::ParseError, "Dimension appears twice");
  expectMeditError(
      [] { parseSol("MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n1\n1 1\n0.5\nDimension 3\nEnd\n"); },
      ErrorCode::ParseError, "Dimension after the data");
}

// from_chars / to_chars (native) and strtod / %.17g (wasm) give the same values and bytes.
TEST(IoMedit, NumbersRoundTripBitExactly) {
  Mesh m;
  m.dimension = 2;
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  char expected[64];
  std::string lines;
  for (int i = 0; i < 20000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    double x;
    std::uint64_t bits = state;
    std::memcpy(&x, &bits, sizeof x);
    if (!std::isfinite(x) || i % 3 == 0) x = double(state >> 11) * 0x1.0p-40 - 4096.0;
    const double y = i % 5 == 0 ? 1e-310 * (i + 1) : 1.0 / (i + 1);  // subnormals too
    m.points.push_back(Vec3(x, y, 0));
    m.pointRefs.push_back(i);
    std::snprintf(expected, sizeof expected, "%.17g %.17g %d\n", x, y, i);
    lines += expected;
  }
  const std::string text = writeMedit(m);
  EXPECT_NE(text.find(lines), std::string::npos);  // printf's bytes
  const Mesh back = parseMedit(text);
  ASSERT_EQ(back.points.size(), m.points.size());
  for (size_t i = 0; i < m.points.size(); ++i) {
    EXPECT_EQ(std::memcmp(&back.points[i], &m.points[i], sizeof(Vec3)), 0) << i;
  }
}

// The newline count that places the lines of a large section in its blocks (a word at a time):
// exact for every length, start and byte, the bytes one bit away from '\n' (and 0x00, 0x80,
// 0xff) included, over more than one flush of the per-byte counts.
TEST(IoMedit, NewlineCountIsExactForEveryByte) {
  std::uint64_t seed = 12345;
  auto next = [&seed] {
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    return unsigned(seed >> 33);
  };
  const unsigned char near[] = {'\n',      '\n' ^ 1,  '\n' ^ 2,   '\n' ^ 4, '\n' ^ 8, '\n' ^ 16,
                                '\n' ^ 32, '\n' ^ 64, '\n' ^ 128, 0,        0x80,     0xff};
  for (int round = 0; round < 400; ++round) {
    const size_t n = round < 100 ? size_t(round) : next() % 6000;
    std::string text(n + 8, 'x');
    const unsigned mode = next() % 3;  // random bytes, bytes near '\n', all newlines
    for (char& ch : text) ch = char(mode == 0 ? next() % 256 : mode == 1 ? near[next() % sizeof near] : '\n');
    const size_t start = next() % 8;
    size_t expected = 0;
    for (size_t i = start; i < start + n; ++i) expected += text[i] == '\n';
    EXPECT_EQ(io_detail::TokenStream::countNewlines(text.data() + start, n), expected)
        << "round " << round << ", " << n << " bytes";
  }
}

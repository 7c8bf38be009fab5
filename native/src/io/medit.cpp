#include "anisomesh/io/medit.h"

#include <algorithm>
#include <climits>
#include <map>

#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/medit_binary.h"
#include "bamg_sections.h"
#include "tokens.h"

namespace anisomesh {
namespace {

using io_detail::appendInt;
using io_detail::appendNumber;
using io_detail::putInt;
using io_detail::putNumber;
using io_detail::TokenStream;

// Sections we read past without keeping: tokens per record (-1: one per dimension).
const std::map<std::string, int>& skippedSections() {
  static const std::map<std::string, int> s{{"Corners", 1},
                                            {"Ridges", 1},
                                            {"RequiredVertices", 1},
                                            {"RequiredEdges", 1},
                                            {"RequiredTriangles", 1},
                                            {"RequiredQuadrilaterals", 1},
                                            {"Tetrahedra", 5},
                                            {"Hexahedra", 9},
                                            {"Prisms", 7},
                                            {"Normals", -1},
                                            {"NormalAtVertices", 2},
                                            {"Tangents", -1},
                                            {"TangentAtVertices", 2}};
  return s;
}

template <size_t N>
void readElements(TokenStream& ts, const char* name, int vertexCount, std::vector<std::array<int, N>>* elems,
                  std::vector<int>* refs) {
  const long long n = ts.count(std::string("the number of ") + name, int(N) + 1);
  // Fast path: one record per line, in parallel chunks (the same values).
  const size_t base = elems->size();
  elems->resize(base + size_t(n));
  refs->resize(base + size_t(n));
  const bool fast = ts.lineRecords(n, [&](size_t i, TokenStream::LineCursor& c) {
    std::array<int, N>& e = (*elems)[base + i];
    long long v = 0;
    for (size_t k = 0; k < N; ++k) {
      if (!c.integer(&v) || v < 1 || v > vertexCount) return false;
      e[k] = int(v - 1);
    }
    if (!c.integer(&v) || v < INT_MIN || v > INT_MAX) return false;
    (*refs)[base + i] = int(v);
    return true;
  });
  if (fast) return;
  elems->resize(base);
  refs->resize(base);
  elems->reserve(base + size_t(n));
  for (long long i = 0; i < n; ++i) {
    std::array<int, N> e;
    for (size_t k = 0; k < N; ++k) {
      const int line = ts.line();
      const long long v = ts.integer([&] {
        return std::string("vertex index ") + std::to_string(k + 1) + " of " + name + " " + std::to_string(i + 1);
      });
      if (v < 1 || v > vertexCount)
        ts.failAt(line, std::string("vertex index ") + std::to_string(v) + " of " + name + " " + std::to_string(i + 1) +
                            " is out of range 1.." + std::to_string(vertexCount));
      e[k] = int(v - 1);
    }
    elems->push_back(e);
    refs->push_back(ts.int32([&] { return std::string("the reference of ") + name + " " + std::to_string(i + 1); }));
  }
}

// Lines per formatting chunk: the pieces are independent of the thread count, so the
// text is the same for any.
constexpr size_t kLinesPerPiece = 16384;

// Appends one piece per chunk of [0, n): line(out, i) formats item i, in parallel.
// Each chunk formats into a string of its own and moves it into its slot at the end: the
// slots are adjacent std::string objects (two per cache line), so appending to them in
// place wrote every character's new length into a cache line the thread formatting the
// neighbour chunk writes too (false sharing).
template <class Line>
void appendPieces(std::vector<std::string>* pieces, size_t n, size_t bytesPerLine, const Line& line) {
  const size_t first = pieces->size();
  pieces->resize(first + chunkCount(n, kLinesPerPiece));
  parallelChunks(n, kLinesPerPiece, [&](size_t chunk, size_t begin, size_t end) {
    std::string out;
    out.reserve((end - begin) * bytesPerLine);
    for (size_t i = begin; i < end; ++i) line(&out, i);
    (*pieces)[first + chunk] = std::move(out);
  });
}

template <size_t N>
void writeElements(std::vector<std::string>* pieces, const char* name, const std::vector<std::array<int, N>>& elems,
                   const std::vector<int>& refs) {
  if (elems.empty()) return;
  std::string head = std::string(name) + "\n";
  appendInt(&head, (long long)elems.size());
  head += "\n";
  pieces->push_back(std::move(head));
  // Each line written in a buffer and appended once (in wasm, libc++'s append and push_back
  // are calls: one per token took about a quarter of the write stage under perf).
  appendPieces(pieces, elems.size(), 8 * (N + 1), [&](std::string* out, size_t i) {
    char line[25 * (N + 1)];
    char* p = line;
    for (size_t k = 0; k < N; ++k) {
      p = putInt(p, elems[i][k] + 1LL);
      *p++ = ' ';
    }
    p = putInt(p, i < refs.size() ? refs[i] : 0);
    *p++ = '\n';
    out->append(line, size_t(p - line));
  });
}

// The Medit text as consecutive pieces (formatted in parallel).
std::vector<std::string> meditPieces(const Mesh& mesh) {
  require(mesh.dimension == 2 || mesh.dimension == 3, ErrorCode::InvalidArgument,
          "Medit output needs dimension 2 or 3, got " + std::to_string(mesh.dimension));
  std::vector<std::string> pieces;
  pieces.push_back("MeshVersionFormatted 2\nDimension " + std::to_string(mesh.dimension) + "\n\n");
  pieces.back() += "Vertices\n" + std::to_string(mesh.points.size()) + "\n";
  appendPieces(&pieces, mesh.points.size(), 24 * size_t(mesh.dimension) + 4, [&](std::string* out, size_t i) {
    char line[3 * 33 + 25];  // up to 3 numbers (32 chars of room each) and a reference
    char* p = line;
    for (int k = 0; k < mesh.dimension; ++k) {
      p = putNumber(p, mesh.points[i][k]);
      *p++ = ' ';
    }
    p = putInt(p, i < mesh.pointRefs.size() ? mesh.pointRefs[i] : 0);
    *p++ = '\n';
    out->append(line, size_t(p - line));
  });
  writeElements<2>(&pieces, "Edges", mesh.edges, mesh.edgeRefs);
  writeElements<3>(&pieces, "Triangles", mesh.triangles, mesh.triangleRefs);
  writeElements<4>(&pieces, "Quadrilaterals", mesh.quads, mesh.quadRefs);
  pieces.push_back("End\n");
  return pieces;
}

// MeshVersionFormatted or Dimension; dataStarted: a data section has been read already.
// Dimension appears once, before the data (a later one would silently change how the
// vertices already read are understood).
void readHeader(TokenStream& ts, const std::string& key, int* version, int* dimension, bool dataStarted) {
  if (key == "Dimension") {
    if (dataStarted) ts.failAt(ts.line(), "Dimension after the data (it must appear once, before the data)");
    if (*dimension != 0) ts.failAt(ts.line(), "Dimension appears twice (it must appear once, before the data)");
  }
  if (key == "MeshVersionFormatted") {
    const int line = ts.line();
    *version = int(ts.integer("the version number after MeshVersionFormatted"));
    if (*version < 1 || *version > 4) ts.failAt(line, "unsupported MeshVersionFormatted " + std::to_string(*version));
  } else {
    const int line = ts.line();
    *dimension = int(ts.integer("the dimension after Dimension"));
    if (*dimension != 2 && *dimension != 3)
      ts.failAt(line, "expected Dimension 2 or 3, got " + std::to_string(*dimension));
  }
}

}  // namespace

std::string writeMedit(const Mesh& mesh) {
  const std::vector<std::string> pieces = meditPieces(mesh);
  size_t size = 0;
  for (const std::string& p : pieces) size += p.size();
  std::string out;
  out.reserve(size);
  for (const std::string& p : pieces) out += p;
  return out;
}

namespace {

// parseMedit on [begin, end) (NUL after it); view (when set) is given back the parsed text.
Mesh parseMeditText(const char* begin, const char* end, TextFileView* view) {
  TokenStream ts(begin, end, "Medit mesh", '#');
  if (view) ts.setRelease([view](const char* p) { view->release(p); });
  Mesh mesh;
  int version = 0, dimension = 0;
  bool haveVertices = false, dataStarted = false;
  while (!ts.atEnd()) {
    const int line = ts.line();
    const std::string key = ts.next().str();
    if (key == "End") break;
    if (key != "MeshVersionFormatted" && key != "Dimension") dataStarted = true;
    if (key == "MeshVersionFormatted" || key == "Dimension") {
      readHeader(ts, key, &version, &dimension, dataStarted);
    } else if (key == "Vertices") {
      if (version == 0) ts.failAt(line, "expected MeshVersionFormatted before Vertices");
      if (dimension == 0) ts.failAt(line, "expected Dimension before Vertices");
      const long long n = ts.count("the number of vertices", dimension + 1);
      mesh.dimension = dimension;
      // Fast path: one vertex per line, in parallel chunks (the same values).
      const size_t base = mesh.points.size(), refBase = mesh.pointRefs.size();
      // (not zero-filled here: each record sets its point, in parallel)
      mesh.points.resize(base + size_t(n));
      mesh.pointRefs.resize(refBase + size_t(n));
      const bool fast = ts.lineRecords(n, [&](size_t i, TokenStream::LineCursor& c) {
        Vec3& p = mesh.points[base + i];
        p.z() = 0.0;
        for (int k = 0; k < dimension; ++k)
          if (!c.number(&p[k])) return false;
        long long ref = 0;
        if (!c.integer(&ref) || ref < INT_MIN || ref > INT_MAX) return false;
        mesh.pointRefs[refBase + i] = int(ref);
        return true;
      });
      if (fast) {
        haveVertices = true;
        continue;
      }
      mesh.points.resize(base);
      mesh.pointRefs.resize(refBase);
      mesh.points.reserve(base + size_t(n));
      for (long long i = 0; i < n; ++i) {
        Vec3 p = Vec3::Zero();
        for (int k = 0; k < dimension; ++k)
          p[k] =
              ts.number([&] { return std::string("coordinate ") + "xyz"[k] + " of vertex " + std::to_string(i + 1); });
        mesh.points.push_back(p);
        mesh.pointRefs.push_back(ts.int32([&] { return "the reference of vertex " + std::to_string(i + 1); }));
      }
      haveVertices = true;
    } else if (key == "Edges" || key == "Triangles" || key == "Quadrilaterals") {
      if (!haveVertices) ts.failAt(line, "expected Vertices before " + key);
      const int nv = mesh.vertexCount();
      if (key == "Edges")
        readElements<2>(ts, "Edges", nv, &mesh.edges, &mesh.edgeRefs);
      else if (key == "Triangles")
        readElements<3>(ts, "Triangles", nv, &mesh.triangles, &mesh.triangleRefs);
      else
        readElements<4>(ts, "Quadrilaterals", nv, &mesh.quads, &mesh.quadRefs);
    } else if (skippedSections().count(key)) {
      int per = skippedSections().at(key);
      if (per < 0) per = dimension > 0 ? dimension : 3;
      const long long n = ts.count("the number of " + key, per);
      for (long long i = 0; i < n * per; ++i) ts.number("a value of " + key);
    } else if (io_detail::skipBamgSection(ts, key)) {
      // BAMG's own sections (bamg_sections.h).
    } else {
      ts.failAt(line,
                "expected a Medit keyword (Vertices, Edges, Triangles, Quadrilaterals, End, ...), got '" + key + "'");
    }
  }
  if (version == 0) ts.failAt(1, "expected MeshVersionFormatted");
  if (dimension != 0) mesh.dimension = dimension;
  return mesh;
}

}  // namespace

Mesh parseMedit(const std::string& text) { return parseMeditText(text.data(), text.data() + text.size(), nullptr); }

Mesh readMeditFile(const std::string& path) {
  TextFileView view(path);  // parsed as it is read: the whole text is not held beside the mesh
  return parseMeditText(view.begin(), view.end(), &view);
}

void writeMeditFile(const std::string& path, const Mesh& mesh) { writeTextFileAtomic(path, meditPieces(mesh)); }

std::string writeSol(const SolData& sol) {
  require(sol.type >= 1 && sol.type <= 3, ErrorCode::InvalidArgument,
          "Medit solutions of type " + std::to_string(sol.type) + " are not supported (1, 2 or 3)");
  require(sol.dimension == 2 || sol.dimension == 3, ErrorCode::InvalidArgument, "solution dimension must be 2 or 3");
  const int per = sol.valuesPerVertex();
  require(sol.values.size() % size_t(per) == 0, ErrorCode::InvalidArgument,
          "solution has " + std::to_string(sol.values.size()) + " values, not a multiple of " + std::to_string(per));
  std::string out = "MeshVersionFormatted 2\nDimension " + std::to_string(sol.dimension) + "\n\nSolAtVertices\n";
  out += std::to_string(sol.count()) + "\n1 " + std::to_string(sol.type) + "\n";
  for (size_t i = 0; i < sol.values.size(); ++i) {
    appendNumber(&out, sol.values[i]);
    out.push_back((i + 1) % size_t(per) == 0 ? '\n' : ' ');
  }
  out += "\nEnd\n";
  return out;
}

namespace {

// parseSol on [begin, end) (NUL after it); view (when set) is given back the parsed text.
SolData parseSolText(const char* begin, const char* end, TextFileView* view) {
  TokenStream ts(begin, end, "Medit sol", '#');
  if (view) ts.setRelease([view](const char* p) { view->release(p); });
  SolData sol;
  int version = 0, dimension = 0;
  bool haveField = false;
  while (!ts.atEnd()) {
    const int line = ts.line();
    const std::string key = ts.next().str();
    if (key == "End") break;
    if (key == "MeshVersionFormatted" || key == "Dimension") {
      readHeader(ts, key, &version, &dimension, haveField);
    } else if (key == "SolAtVertices") {
      if (dimension == 0) ts.failAt(line, "expected Dimension before SolAtVertices");
      if (haveField) ts.failAt(line, "only one SolAtVertices section is supported");
      const long long n = ts.count("the number of vertices of SolAtVertices", 1);
      const int fieldsLine = ts.line();
      const long long fields = ts.integer("the number of solution fields");
      if (fields != 1) ts.failAt(fieldsLine, "expected 1 solution field, got " + std::to_string(fields));
      const int typeLine = ts.line();
      const long long type = ts.integer("the solution type (1 = scalar, 2 = vector, 3 = tensor)");
      if (type < 1 || type > 3)
        ts.failAt(typeLine,
                  "expected solution type 1 (scalar), 2 (vector) or 3 (symmetric tensor), got " + std::to_string(type));
      sol.dimension = dimension;
      sol.type = int(type);
      const int per = sol.valuesPerVertex();
      if (n > 0 && ts.atEnd()) ts.fail("the values of vertex 1");
      // Fast path: one vertex's values per line, in parallel chunks (the same values).
      sol.values.resize(size_t(n) * size_t(per));
      const bool fast = ts.lineRecords(n, [&](size_t i, TokenStream::LineCursor& c) {
        for (int k = 0; k < per; ++k)
          if (!c.number(&sol.values[i * size_t(per) + size_t(k)])) return false;
        return true;
      });
      if (fast) {
        haveField = true;
        continue;
      }
      sol.values.clear();
      sol.values.reserve(size_t(n) * size_t(per));
      for (long long i = 0; i < n; ++i)
        for (int k = 0; k < per; ++k)
          sol.values.push_back(
              ts.number([&] { return "value " + std::to_string(k + 1) + " of vertex " + std::to_string(i + 1); }));
      haveField = true;
    } else {
      ts.failAt(line, "expected MeshVersionFormatted, Dimension, SolAtVertices or End, got '" + key + "'");
    }
  }
  if (!haveField) ts.failAt(ts.line(), "expected a SolAtVertices section");
  return sol;
}

}  // namespace

SolData parseSol(const std::string& text) { return parseSolText(text.data(), text.data() + text.size(), nullptr); }

SolData readSolFile(const std::string& path) {
  if (fileExtension(path) == "solb") return parseSolBinary(readTextFile(path));
  TextFileView view(path);  // parsed as it is read
  return parseSolText(view.begin(), view.end(), &view);
}

void writeSolFile(const std::string& path, const SolData& sol) {
  writeTextFileAtomic(path, fileExtension(path) == "solb" ? writeSolBinary(sol) : writeSol(sol));
}

std::vector<Metric> solToMetrics(const SolData& sol, int vertexCount) {
  require(sol.count() == vertexCount, ErrorCode::ParseError,
          "the solution has " + std::to_string(sol.count()) + " values but the mesh has " +
              std::to_string(vertexCount) + " vertices");
  require(sol.type != 2, ErrorCode::InvalidArgument, "vector solutions (type 2) cannot drive a metric");
  require(sol.dimension == 2 || sol.type == 1, ErrorCode::InvalidArgument,
          "3D tensor solutions cannot drive a planar metric");
  std::vector<Metric> metrics(size_t(std::max(vertexCount, 0)));
  const int per = sol.valuesPerVertex();
  // In parallel chunks (an eigen decomposition per vertex); the lowest chunk's error is
  // rethrown, so the message names the first invalid vertex for any thread count.
  parallelChunks(metrics.size(), 8192, [&](size_t, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const double* v = &sol.values[i * size_t(per)];
      try {
        metrics[i] = sol.type == 1 ? Metric::isotropic(v[0]) : Metric::fromTensor(v[0], v[1], v[2]);
      } catch (const Error& err) {
        throw Error(err.code(), "solution value of vertex " + std::to_string(i + 1) + ": " + err.what());
      }
    }
  });
  return metrics;
}

SolData metricsToSol(const std::vector<Metric>& metrics) {
  SolData sol;
  sol.dimension = 2;
  sol.type = 3;
  for (const Metric& m : metrics) {
    const Mat2 t = m.tensor();
    sol.values.insert(sol.values.end(), {t(0, 0), t(0, 1), t(1, 1)});
  }
  return sol;
}

}  // namespace anisomesh

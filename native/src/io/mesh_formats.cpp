#include "anisomesh/io/mesh_formats.h"

#include <cmath>
#include <sstream>

#include "anisomesh/core/error.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/gmsh.h"
#include "anisomesh/io/medit.h"
#include "anisomesh/io/medit_binary.h"
#include "tokens.h"

namespace anisomesh {
namespace {

using io_detail::appendInt;
using io_detail::appendNumber;
using io_detail::appendXyzLine;
using io_detail::TokenStream;

void setPlanarIfFlat(Mesh* mesh) {
  mesh->dimension = 2;
  for (const Vec3& p : mesh->points)
    if (p.z() != 0.0) {
      mesh->dimension = 3;
      return;
    }
}

void expectKeyword(TokenStream& ts, const std::string& key) {
  if (ts.atEnd() || ts.peek().str() != key) ts.fail("'" + key + "'");
  ts.next();
}

}  // namespace

MeshFormat meshFormatFromPath(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == "mesh") return MeshFormat::Medit;
  if (ext == "vtk") return MeshFormat::Vtk;
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "msh") return MeshFormat::Gmsh;
  if (ext == "meshb") return MeshFormat::MeditBinary;
  throw Error(ErrorCode::InvalidArgument,
              "unknown mesh format of '" + path + "': expected the extension .mesh, .meshb, .vtk, .obj or .msh");
}

std::string writeVtk(const Mesh& mesh) {
  std::string out = "# vtk DataFile Version 3.0\nanisomesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  out += "POINTS " + std::to_string(mesh.points.size()) + " double\n";
  for (const Vec3& p : mesh.points) {
    appendXyzLine(&out, p);
  }
  const size_t cells = mesh.edges.size() + mesh.triangles.size() + mesh.quads.size();
  const size_t size = 3 * mesh.edges.size() + 4 * mesh.triangles.size() + 5 * mesh.quads.size();
  out += "CELLS " + std::to_string(cells) + " " + std::to_string(size) + "\n";
  auto cell = [&out](const int* v, int n) {
    appendInt(&out, n);
    for (int k = 0; k < n; ++k) {
      out.push_back(' ');
      appendInt(&out, v[k]);
    }
    out.push_back('\n');
  };
  for (const auto& e : mesh.edges) cell(e.data(), 2);
  for (const auto& t : mesh.triangles) cell(t.data(), 3);
  for (const auto& q : mesh.quads) cell(q.data(), 4);
  out += "CELL_TYPES " + std::to_string(cells) + "\n";
  for (size_t i = 0; i < mesh.edges.size(); ++i) out += "3\n";
  for (size_t i = 0; i < mesh.triangles.size(); ++i) out += "5\n";
  for (size_t i = 0; i < mesh.quads.size(); ++i) out += "9\n";
  out += "CELL_DATA " + std::to_string(cells) + "\nSCALARS ref int 1\nLOOKUP_TABLE default\n";
  auto refs = [&out](const std::vector<int>& r, size_t n) {
    for (size_t i = 0; i < n; ++i) {
      appendInt(&out, i < r.size() ? r[i] : 0);
      out.push_back('\n');
    }
  };
  refs(mesh.edgeRefs, mesh.edges.size());
  refs(mesh.triangleRefs, mesh.triangles.size());
  refs(mesh.quadRefs, mesh.quads.size());
  return out;
}

Mesh parseVtk(const std::string& text) {
  // The first two lines are free-form (version, title): check them line-wise.
  std::istringstream lines(text);
  std::string l1, l2;
  std::getline(lines, l1);
  if (l1.rfind("# vtk DataFile", 0) != 0)
    throw Error(ErrorCode::ParseError, "VTK line 1: expected '# vtk DataFile Version ...'");
  std::getline(lines, l2);
  const size_t skip = std::min(text.size(), l1.size() + 1 + l2.size() + 1);
  // Tokenize the rest, keeping line numbers (offset by the two header lines).
  const std::string body = text.substr(skip);
  TokenStream ts(body, "VTK", 0, 3);
  expectKeyword(ts, "ASCII");
  expectKeyword(ts, "DATASET");
  expectKeyword(ts, "UNSTRUCTURED_GRID");
  Mesh mesh;
  std::vector<int> cellTypes;
  std::vector<std::vector<int>> cells;
  std::vector<int> cellLines;
  std::vector<int> refs;
  while (!ts.atEnd()) {
    const int line = ts.line();
    const std::string key = ts.next().str();
    if (key == "POINTS") {
      const long long n = ts.count("the number of points", 3);
      ts.next();  // data type (float, double)
      for (long long i = 0; i < n; ++i) {
        Vec3 p;
        for (int k = 0; k < 3; ++k)
          p[k] = ts.number([&] { return std::string("coordinate ") + "xyz"[k] + " of point " + std::to_string(i); });
        mesh.points.push_back(p);
      }
    } else if (key == "CELLS") {
      const long long n = ts.count("the number of cells", 2);
      ts.integer("the size of the CELLS list");
      for (long long i = 0; i < n; ++i) {
        const int cl = ts.line();
        const long long k = ts.integer("the vertex count of cell " + std::to_string(i));
        if (k < 1 || k > 8)
          ts.failAt(cl, "cell " + std::to_string(i) + " has an unsupported vertex count " + std::to_string(k));
        std::vector<int> c;
        for (long long j = 0; j < k; ++j) {
          const long long v = ts.integer([&] { return "a vertex index of cell " + std::to_string(i); });
          if (v < 0 || v >= (long long)mesh.points.size())
            ts.failAt(cl, "vertex index " + std::to_string(v) + " of cell " + std::to_string(i) +
                              " is out of range 0.." + std::to_string((long long)mesh.points.size() - 1));
          c.push_back(int(v));
        }
        cells.push_back(std::move(c));
        cellLines.push_back(cl);
      }
    } else if (key == "CELL_TYPES") {
      const long long n = ts.count("the number of cell types", 1);
      if (n != (long long)cells.size())
        ts.failAt(line,
                  "CELL_TYPES has " + std::to_string(n) + " entries but CELLS has " + std::to_string(cells.size()));
      for (long long i = 0; i < n; ++i)
        cellTypes.push_back(int(ts.integer([&] { return "the type of cell " + std::to_string(i); })));
    } else if (key == "CELL_DATA") {
      const long long n = ts.count("the number of cell data values", 1);
      if (n != (long long)cells.size())
        ts.failAt(line,
                  "CELL_DATA has " + std::to_string(n) + " entries but CELLS has " + std::to_string(cells.size()));
      expectKeyword(ts, "SCALARS");
      ts.next();  // name
      ts.next();  // type
      if (!ts.atEnd() && ts.peek().str() != "LOOKUP_TABLE") ts.integer("the number of components");
      expectKeyword(ts, "LOOKUP_TABLE");
      ts.next();
      for (long long i = 0; i < n; ++i)
        refs.push_back(int(std::lround(ts.number([&] { return "the value of cell " + std::to_string(i); }))));
      break;  // further attributes are not needed
    } else if (key == "POINT_DATA") {
      break;
    } else {
      ts.failAt(line, "expected POINTS, CELLS, CELL_TYPES or CELL_DATA, got '" + key + "'");
    }
  }
  if (cellTypes.size() != cells.size())
    ts.failAt(ts.line(), "expected CELL_TYPES for the " + std::to_string(cells.size()) + " cells");
  for (size_t i = 0; i < cells.size(); ++i) {
    const int ref = i < refs.size() ? refs[i] : 0;
    const std::vector<int>& c = cells[i];
    const int type = cellTypes[i];
    const size_t want = type == 3 ? 2 : type == 5 ? 3 : type == 9 ? 4 : 0;
    if (want == 0)
      ts.failAt(cellLines[i], "cell " + std::to_string(i) + " has unsupported VTK type " + std::to_string(type) +
                                  " (3, 5 or 9 expected)");
    if (c.size() != want)
      ts.failAt(cellLines[i], "cell " + std::to_string(i) + " of type " + std::to_string(type) + " needs " +
                                  std::to_string(want) + " vertices");
    if (type == 3) {
      mesh.edges.push_back({c[0], c[1]});
      mesh.edgeRefs.push_back(ref);
    }
    if (type == 5) {
      mesh.triangles.push_back({c[0], c[1], c[2]});
      mesh.triangleRefs.push_back(ref);
    }
    if (type == 9) {
      mesh.quads.push_back({c[0], c[1], c[2], c[3]});
      mesh.quadRefs.push_back(ref);
    }
  }
  mesh.pointRefs.assign(mesh.points.size(), 0);
  setPlanarIfFlat(&mesh);
  return mesh;
}

std::string writeObj(const Mesh& mesh) {
  std::string out = "# anisomesh\n";
  for (const Vec3& p : mesh.points) {
    out += "v ";
    appendXyzLine(&out, p);
  }
  auto element = [&out](const char* tag, const int* v, int n) {
    out += tag;
    for (int k = 0; k < n; ++k) {
      out.push_back(' ');
      appendInt(&out, v[k] + 1LL);
    }
    out.push_back('\n');
  };
  for (const auto& e : mesh.edges) element("l", e.data(), 2);
  for (const auto& t : mesh.triangles) element("f", t.data(), 3);
  for (const auto& q : mesh.quads) element("f", q.data(), 4);
  return out;
}

Mesh parseObj(const std::string& text) {
  Mesh mesh;
  struct Pending {
    std::vector<long long> v;
    int line;
    char kind;
  };
  std::vector<Pending> pending;
  std::istringstream in(text);
  std::string lineText;
  int line = 0;
  while (std::getline(in, lineText)) {
    ++line;
    TokenStream ts(lineText, "OBJ", '#', line);
    if (ts.atEnd()) continue;
    const std::string key = ts.next().str();
    auto here = [&](const std::string& m) {
      throw Error(ErrorCode::ParseError, "OBJ line " + std::to_string(line) + ": " + m);
    };
    if (key == "v") {
      Vec3 p = Vec3::Zero();
      for (int k = 0; k < 3; ++k) {
        if (k == 2 && ts.atEnd()) break;
        p[k] = ts.number(std::string("coordinate ") + "xyz"[k] + " of a vertex");
      }
      mesh.points.push_back(p);
    } else if (key == "f" || key == "l") {
      Pending p{{}, line, key[0]};
      while (!ts.atEnd()) {
        const std::string tok = ts.next().str();
        const std::string first = tok.substr(0, tok.find('/'));
        char* stop = nullptr;
        const long long v = std::strtoll(first.c_str(), &stop, 10);
        if (first.empty() || *stop != '\0' || v == 0) here("expected a vertex index, got '" + tok + "'");
        // Negative indices count back from the vertices read so far.
        p.v.push_back(v > 0 ? v - 1 : (long long)mesh.points.size() + v);
      }
      if (key == "f" && (p.v.size() < 3 || p.v.size() > 4))
        here("expected a face with 3 or 4 vertices, got " + std::to_string(p.v.size()));
      if (key == "l" && p.v.size() < 2) here("expected a line with at least 2 vertices");
      pending.push_back(std::move(p));
    }
    // Other statements (vt, vn, g, o, s, usemtl, mtllib) carry nothing we keep.
  }
  const long long n = (long long)mesh.points.size();
  for (const Pending& p : pending) {
    for (long long v : p.v)
      if (v < 0 || v >= n)
        throw Error(ErrorCode::ParseError, "OBJ line " + std::to_string(p.line) + ": vertex index " +
                                               std::to_string(v + 1) + " is out of range 1.." + std::to_string(n));
    if (p.kind == 'l') {
      for (size_t k = 0; k + 1 < p.v.size(); ++k) {
        mesh.edges.push_back({int(p.v[k]), int(p.v[k + 1])});
        mesh.edgeRefs.push_back(0);
      }
    } else if (p.v.size() == 3) {
      mesh.triangles.push_back({int(p.v[0]), int(p.v[1]), int(p.v[2])});
      mesh.triangleRefs.push_back(0);
    } else {
      mesh.quads.push_back({int(p.v[0]), int(p.v[1]), int(p.v[2]), int(p.v[3])});
      mesh.quadRefs.push_back(0);
    }
  }
  mesh.pointRefs.assign(mesh.points.size(), 0);
  setPlanarIfFlat(&mesh);
  return mesh;
}

std::string writeMeshString(const Mesh& mesh, MeshFormat format) {
  switch (format) {
    case MeshFormat::Medit:
      return writeMedit(mesh);
    case MeshFormat::Vtk:
      return writeVtk(mesh);
    case MeshFormat::Obj:
      return writeObj(mesh);
    case MeshFormat::Gmsh:
      return writeGmsh(mesh, GmshVersion::V41);
    case MeshFormat::Gmsh22:
      return writeGmsh(mesh, GmshVersion::V22);
    case MeshFormat::MeditBinary:
      return writeMeditBinary(mesh);
  }
  return writeMedit(mesh);
}

Mesh parseMeshString(const std::string& text, MeshFormat format) {
  switch (format) {
    case MeshFormat::Medit:
      return parseMedit(text);
    case MeshFormat::Vtk:
      return parseVtk(text);
    case MeshFormat::Obj:
      return parseObj(text);
    case MeshFormat::Gmsh:
    case MeshFormat::Gmsh22:
      return parseGmsh(text);
    case MeshFormat::MeditBinary:
      return parseMeditBinary(text);
  }
  return parseMedit(text);
}

void writeMeshFile(const std::string& path, const Mesh& mesh) {
  const MeshFormat format = meshFormatFromPath(path);
  if (format == MeshFormat::Medit) return writeMeditFile(path, mesh);  // written piece by piece
  writeTextFileAtomic(path, writeMeshString(mesh, format));
}

Mesh readMeshFile(const std::string& path) {
  const MeshFormat format = meshFormatFromPath(path);
  if (format == MeshFormat::Medit) return readMeditFile(path);  // parsed as it is read
  return parseMeshString(readTextFile(path), format);
}

}  // namespace anisomesh

#include "anisomesh/io/medit_binary.h"

#include <cstdint>
#include <cstring>
#include <limits>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

// libMeshb keyword codes.
enum Keyword : int {
  kDimension = 3,
  kVertices = 4,
  kEdges = 5,
  kTriangles = 6,
  kQuadrilaterals = 7,
  kCorners = 13,
  kRidges = 14,
  kRequiredVertices = 15,
  kEnd = 54,
  kSolAtVertices = 62
};

// The name of a keyword code for messages.
std::string keywordName(int code) {
  switch (code) {
    case kDimension:
      return "Dimension";
    case kVertices:
      return "Vertices";
    case kEdges:
      return "Edges";
    case kTriangles:
      return "Triangles";
    case kQuadrilaterals:
      return "Quadrilaterals";
    case kCorners:
      return "Corners";
    case kRidges:
      return "Ridges";
    case kRequiredVertices:
      return "RequiredVertices";
    case kEnd:
      return "End";
    case kSolAtVertices:
      return "SolAtVertices";
    default:
      return "keyword " + std::to_string(code);
  }
}

// Reads the words of a binary Medit file: bounds-checked, in the file's byte order and
// widths (set by the header).
class BinaryReader {
 public:
  BinaryReader(const std::string& bytes, const char* what) : b_(bytes), what_(what) {}

  // The code word and the version; fails unless code is 1 in either byte order.
  void readHeader() {
    if (b_.size() < 8) fail("expected the 8-byte header (code 1, version)");
    const std::uint32_t code = std::uint32_t(raw(4));
    if (code == 0x01000000u) {
      swap_ = true;
    } else if (code != 1) {
      pos_ = 0;
      fail("expected the code 1 that starts a binary Medit file (is it a text file?)");
    }
    const size_t at = pos_;
    version_ = int(std::int32_t(raw(4)));
    if (version_ < 1 || version_ > 4) {
      pos_ = at;
      fail("unsupported version " + std::to_string(version_) + " (1 to 4)");
    }
  }
  bool atEnd() const { return pos_ >= b_.size(); }
  size_t offset() const { return pos_; }
  size_t remaining() const { return b_.size() - pos_; }
  void seek(size_t pos) { pos_ = pos; }
  void setSection(const std::string& name) { section_ = name; }
  size_t intBytes() const { return version_ >= 4 ? 8 : 4; }
  size_t realBytes() const { return version_ == 1 ? 4 : 8; }
  size_t positionBytes() const { return version_ >= 3 ? 8 : 4; }

  // A 32-bit word (keyword codes, the dimension, solution types).
  int word() { return int(std::int32_t(raw(4))); }
  // The position of the next keyword.
  std::int64_t position() { return positionBytes() == 8 ? std::int64_t(raw(8)) : std::int64_t(std::int32_t(raw(4))); }
  // An integer of the file's integer width.
  std::int64_t integer() { return intBytes() == 8 ? std::int64_t(raw(8)) : std::int64_t(std::int32_t(raw(4))); }
  // A real of the file's real width.
  double real() {
    if (realBytes() == 4) {
      const std::uint32_t u = std::uint32_t(raw(4));
      float f;
      std::memcpy(&f, &u, 4);
      return f;
    }
    const std::uint64_t u = raw(8);
    double d;
    std::memcpy(&d, &u, 8);
    return d;
  }
  // A record count: fails unless count records of recordBytes each fit in the bytes left.
  long long count(const std::string& items, size_t recordBytes) {
    const size_t at = pos_;
    const std::int64_t n = integer();
    const size_t left = remaining();
    if (n < 0) {
      pos_ = at;
      fail("negative number of " + items + ": " + std::to_string(n));
    }
    if (std::uint64_t(n) > left / recordBytes) {
      pos_ = at;
      fail(std::to_string(n) + " " + items + " need " + std::to_string(recordBytes) + " bytes each but only " +
           std::to_string(left) + " bytes follow");
    }
    return (long long)n;
  }
  // A 32-bit reference (a 64-bit one of version 4 must fit).
  int reference(const std::string& of) {
    const size_t at = pos_;
    const std::int64_t r = integer();
    if (r < std::numeric_limits<int>::min() || r > std::numeric_limits<int>::max()) {
      pos_ = at;
      fail("the reference " + std::to_string(r) + " of " + of + " does not fit in 32 bits");
    }
    return int(r);
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(ErrorCode::ParseError, std::string(what_) + ", byte " + std::to_string(pos_) +
                                           (section_.empty() ? "" : " (" + section_ + ")") + ": " + message);
  }

 private:
  std::uint64_t raw(size_t n) {
    if (remaining() < n) fail("the file ends after " + std::to_string(b_.size()) + " bytes, inside the data");
    std::uint64_t v = 0;
    for (size_t k = 0; k < n; ++k) {
      const size_t i = swap_ ? k : n - 1 - k;  // little-endian unless swapped
      v = (v << 8) | std::uint8_t(b_[pos_ + i]);
    }
    pos_ += n;
    return v;
  }

  const std::string& b_;
  const char* what_;
  size_t pos_ = 0;
  bool swap_ = false;
  int version_ = 0;
  std::string section_;
};

// Little-endian words appended to a byte string.
void putWord(std::string* out, std::uint64_t v, size_t n) {
  for (size_t k = 0; k < n; ++k) out->push_back(char((v >> (8 * k)) & 0xff));
}
void putReal(std::string* out, double d) {
  std::uint64_t u;
  std::memcpy(&u, &d, 8);
  putWord(out, u, 8);
}

// Writes keyword headers with the positions of the next keyword (version 2 or 3).
struct BinaryWriter {
  std::string out;
  size_t positionBytes = 4;
  // The header: code 1 and version 2, or 3 (64-bit positions) when the file, of
  // sizeAtVersion2 bytes at version 2, would reach 2 GiB at version 3.
  BinaryWriter(size_t sizeAtVersion2, size_t keywords) {
    const bool big = sizeAtVersion2 + 4 * keywords >= (size_t(1) << 31);
    positionBytes = big ? 8 : 4;
    putWord(&out, 1, 4);
    putWord(&out, big ? 3 : 2, 4);
  }
  // A keyword whose data takes dataBytes (count included).
  void keyword(int code, size_t dataBytes) {
    putWord(&out, std::uint32_t(code), 4);
    putWord(&out, code == kEnd ? 0 : out.size() + positionBytes + dataBytes, positionBytes);
  }
};

// Reads the Dimension keyword's value.
int readDimension(BinaryReader& r, int dimension) {
  if (dimension != 0) r.fail("Dimension appears twice (it must appear once, before the data)");
  const size_t at = r.offset();
  const int d = r.word();
  if (d != 2 && d != 3) {
    r.seek(at);
    r.fail("expected Dimension 2 or 3, got " + std::to_string(d));
  }
  return d;
}

// Skips a keyword by the position of the next one, read at byte positionAt (it must lie
// ahead, in the file).
void skipKeyword(BinaryReader& r, std::int64_t next, size_t positionAt, size_t size) {
  if (next <= std::int64_t(r.offset()) || std::uint64_t(next) > size) {
    r.seek(positionAt);
    r.fail("the position of the next keyword, " + std::to_string(next) + ", is not ahead of it within the " +
           std::to_string(size) + " bytes");
  }
  r.seek(size_t(next));
}

template <size_t N>
void readBinaryElements(BinaryReader& r, const char* name, int vertexCount, std::vector<std::array<int, N>>* elems,
                        std::vector<int>* refs) {
  const long long n = r.count(name, (N + 1) * r.intBytes());
  elems->reserve(elems->size() + size_t(n));
  refs->reserve(refs->size() + size_t(n));
  for (long long i = 0; i < n; ++i) {
    std::array<int, N> e;
    for (size_t k = 0; k < N; ++k) {
      const size_t at = r.offset();
      const std::int64_t v = r.integer();
      if (v < 1 || v > vertexCount) {
        r.seek(at);
        r.fail(std::string("vertex index ") + std::to_string(v) + " of " + name + " " + std::to_string(i + 1) +
               " is out of range 1.." + std::to_string(vertexCount));
      }
      e[k] = int(v - 1);
    }
    elems->push_back(e);
    refs->push_back(r.reference(std::string(name) + " " + std::to_string(i + 1)));
  }
}

template <size_t N>
void writeBinaryElements(BinaryWriter& w, int code, const std::vector<std::array<int, N>>& elems,
                         const std::vector<int>& refs) {
  if (elems.empty()) return;
  w.keyword(code, 4 + elems.size() * (N + 1) * 4);
  putWord(&w.out, std::uint32_t(elems.size()), 4);
  for (size_t i = 0; i < elems.size(); ++i) {
    for (size_t k = 0; k < N; ++k) putWord(&w.out, std::uint32_t(elems[i][k] + 1), 4);
    putWord(&w.out, std::uint32_t(i < refs.size() ? refs[i] : 0), 4);
  }
}

}  // namespace

std::string writeMeditBinary(const Mesh& mesh) {
  require(mesh.dimension == 2 || mesh.dimension == 3, ErrorCode::InvalidArgument,
          "Medit output needs dimension 2 or 3, got " + std::to_string(mesh.dimension));
  require(mesh.points.size() < (size_t(1) << 31), ErrorCode::InvalidArgument, "too many vertices for .meshb");
  const size_t d = size_t(mesh.dimension);
  const size_t sections = 3 + !mesh.edges.empty() + !mesh.triangles.empty() + !mesh.quads.empty();
  // Header, Dimension, End, then each section: 12 bytes (code, position, count) and its records.
  const size_t size = 8 + 12 + 8 + 12 + mesh.points.size() * (8 * d + 4) +
                      (mesh.edges.empty() ? 0 : 12 + mesh.edges.size() * 12) +
                      (mesh.triangles.empty() ? 0 : 12 + mesh.triangles.size() * 16) +
                      (mesh.quads.empty() ? 0 : 12 + mesh.quads.size() * 20);
  BinaryWriter w(size, sections);
  w.out.reserve(size + 4 * sections);
  w.keyword(kDimension, 4);
  putWord(&w.out, d, 4);
  w.keyword(kVertices, 4 + mesh.points.size() * (8 * d + 4));
  putWord(&w.out, mesh.points.size(), 4);
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    for (size_t k = 0; k < d; ++k) putReal(&w.out, mesh.points[i][int(k)]);
    putWord(&w.out, std::uint32_t(i < mesh.pointRefs.size() ? mesh.pointRefs[i] : 0), 4);
  }
  writeBinaryElements<2>(w, kEdges, mesh.edges, mesh.edgeRefs);
  writeBinaryElements<3>(w, kTriangles, mesh.triangles, mesh.triangleRefs);
  writeBinaryElements<4>(w, kQuadrilaterals, mesh.quads, mesh.quadRefs);
  w.keyword(kEnd, 0);
  return w.out;
}

Mesh parseMeditBinary(const std::string& bytes) {
  BinaryReader r(bytes, "Medit binary mesh");
  r.readHeader();
  Mesh mesh;
  int dimension = 0;
  bool haveVertices = false, dataStarted = false, ended = false;
  while (!r.atEnd()) {
    r.setSection("");
    const int code = r.word();
    r.setSection(keywordName(code));
    if (code == kEnd) {  // its position (0) may be left out, not cut
      if (r.remaining() > 0 && r.remaining() < r.positionBytes()) r.fail("the file ends inside the End keyword");
      ended = true;
      break;
    }
    const size_t positionAt = r.offset();
    const std::int64_t next = r.position();
    if (code == kDimension) {
      if (dataStarted) r.fail("Dimension after the data (it must appear once, before the data)");
      dimension = readDimension(r, dimension);
      continue;
    }
    dataStarted = true;
    if (code == kVertices) {
      if (dimension == 0) r.fail("expected Dimension before Vertices");
      if (haveVertices) r.fail("Vertices appears twice");
      const long long n = r.count("vertices", size_t(dimension) * r.realBytes() + r.intBytes());
      mesh.dimension = dimension;
      mesh.points.reserve(size_t(n));
      mesh.pointRefs.reserve(size_t(n));
      for (long long i = 0; i < n; ++i) {
        Vec3 p = Vec3::Zero();
        for (int k = 0; k < dimension; ++k) p[k] = r.real();
        mesh.points.push_back(p);
        mesh.pointRefs.push_back(r.reference("vertex " + std::to_string(i + 1)));
      }
      haveVertices = true;
    } else if (code == kEdges || code == kTriangles || code == kQuadrilaterals) {
      if (!haveVertices) r.fail("expected Vertices before " + keywordName(code));
      const int nv = mesh.vertexCount();
      if (code == kEdges) readBinaryElements<2>(r, "Edges", nv, &mesh.edges, &mesh.edgeRefs);
      if (code == kTriangles) readBinaryElements<3>(r, "Triangles", nv, &mesh.triangles, &mesh.triangleRefs);
      if (code == kQuadrilaterals) readBinaryElements<4>(r, "Quadrilaterals", nv, &mesh.quads, &mesh.quadRefs);
    } else if (code == kCorners || code == kRidges || code == kRequiredVertices) {
      const long long n = r.count(keywordName(code), r.intBytes());
      r.seek(r.offset() + size_t(n) * r.intBytes());
    } else {
      skipKeyword(r, next, positionAt, bytes.size());
    }
  }
  r.setSection("");
  if (!ended) r.fail("expected the End keyword");
  if (dimension == 0) r.fail("expected a Dimension keyword");
  mesh.dimension = dimension;
  return mesh;
}

std::string writeSolBinary(const SolData& sol) {
  require(sol.type >= 1 && sol.type <= 3, ErrorCode::InvalidArgument,
          "Medit solutions of type " + std::to_string(sol.type) + " are not supported (1, 2 or 3)");
  require(sol.dimension == 2 || sol.dimension == 3, ErrorCode::InvalidArgument, "solution dimension must be 2 or 3");
  const size_t per = size_t(sol.valuesPerVertex());
  require(sol.values.size() % per == 0, ErrorCode::InvalidArgument,
          "solution has " + std::to_string(sol.values.size()) + " values, not a multiple of " + std::to_string(per));
  const size_t size = 8 + 12 + 20 + 8 * sol.values.size() + 8;  // header, Dimension, SolAtVertices, End
  BinaryWriter w(size, 3);
  w.keyword(kDimension, 4);
  putWord(&w.out, std::uint32_t(sol.dimension), 4);
  w.keyword(kSolAtVertices, 12 + 8 * sol.values.size());
  putWord(&w.out, std::uint32_t(sol.count()), 4);
  putWord(&w.out, 1, 4);
  putWord(&w.out, std::uint32_t(sol.type), 4);
  for (double v : sol.values) putReal(&w.out, v);
  w.keyword(kEnd, 0);
  return w.out;
}

SolData parseSolBinary(const std::string& bytes) {
  BinaryReader r(bytes, "Medit binary sol");
  r.readHeader();
  SolData sol;
  int dimension = 0;
  bool haveField = false, ended = false;
  while (!r.atEnd()) {
    r.setSection("");
    const int code = r.word();
    r.setSection(keywordName(code));
    if (code == kEnd) {  // its position (0) may be left out, not cut
      if (r.remaining() > 0 && r.remaining() < r.positionBytes()) r.fail("the file ends inside the End keyword");
      ended = true;
      break;
    }
    const size_t positionAt = r.offset();
    const std::int64_t next = r.position();
    if (code == kDimension) {
      if (haveField) r.fail("Dimension after the data (it must appear once, before the data)");
      dimension = readDimension(r, dimension);
    } else if (code == kSolAtVertices) {
      if (dimension == 0) r.fail("expected Dimension before SolAtVertices");
      if (haveField) r.fail("only one SolAtVertices section is supported");
      const size_t countAt = r.offset();
      const std::int64_t n = r.integer();
      const int fields = r.word();
      if (fields != 1) r.fail("expected 1 solution field, got " + std::to_string(fields));
      const int type = r.word();
      if (type < 1 || type > 3)
        r.fail("expected solution type 1 (scalar), 2 (vector) or 3 (symmetric tensor), got " + std::to_string(type));
      sol.dimension = dimension;
      sol.type = type;
      const size_t per = size_t(sol.valuesPerVertex());
      if (n < 0 || std::uint64_t(n) > r.remaining() / (per * r.realBytes())) {
        r.seek(countAt);
        r.fail(std::to_string(n) + " solution values of " + std::to_string(per * r.realBytes()) +
               " bytes each do not fit in the " + std::to_string(bytes.size()) + " bytes of the file");
      }
      sol.values.reserve(size_t(n) * per);
      for (std::int64_t i = 0; i < n * std::int64_t(per); ++i) sol.values.push_back(r.real());
      haveField = true;
    } else {
      skipKeyword(r, next, positionAt, bytes.size());
    }
  }
  r.setSection("");
  if (!ended) r.fail("expected the End keyword");
  if (!haveField) r.fail("expected a SolAtVertices section");
  return sol;
}

}  // namespace anisomesh

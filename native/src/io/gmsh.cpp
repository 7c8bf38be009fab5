// Gmsh .msh ASCII 4.1 and 2.2 (see gmsh.h).
#include "anisomesh/io/gmsh.h"

#include <algorithm>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

#include "anisomesh/core/error.h"
#include "tokens.h"

namespace anisomesh {
namespace {

using io_detail::appendInt;
using io_detail::appendXyzLine;
using io_detail::TokenStream;

// Gmsh element types: 1 line, 2 triangle, 3 quad, 15 point.
struct Block {
  int dim;
  int type;
  int ref;
  std::vector<const int*> nodes;  // into the mesh's arrays
  int arity;
};

// Elements grouped by (dimension, ref) in a fixed order: edges, triangles, quads, refs ascending.
std::vector<Block> blocks(const Mesh& mesh) {
  std::vector<Block> out;
  auto group = [&](int dim, int type, int arity, const auto& elements, const std::vector<int>& refs) {
    std::map<int, size_t> index;
    for (size_t i = 0; i < elements.size(); ++i) {
      const int ref = i < refs.size() ? refs[i] : 0;
      auto [it, added] = index.emplace(ref, out.size());
      if (added) out.push_back({dim, type, ref, {}, arity});
      out[it->second].nodes.push_back(elements[i].data());
    }
  };
  group(1, 1, 2, mesh.edges, mesh.edgeRefs);
  group(2, 2, 3, mesh.triangles, mesh.triangleRefs);
  group(2, 3, 4, mesh.quads, mesh.quadRefs);
  std::stable_sort(out.begin(), out.end(), [](const Block& a, const Block& b) {
    return a.dim != b.dim ? a.dim < b.dim : (a.ref != b.ref ? a.ref < b.ref : a.type < b.type);
  });
  return out;
}

void appendElementNodes(std::string* out, const Block& b, size_t i) {
  for (int k = 0; k < b.arity; ++k) {
    out->push_back(' ');
    appendInt(out, b.nodes[i][k] + 1);
  }
  out->push_back('\n');
}

std::string writeV22(const Mesh& mesh) {
  std::string out = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n";
  appendInt(&out, mesh.vertexCount());
  out.push_back('\n');
  for (int i = 0; i < mesh.vertexCount(); ++i) {
    appendInt(&out, i + 1);
    out.push_back(' ');
    appendXyzLine(&out, mesh.points[i]);
  }
  out += "$EndNodes\n$Elements\n";
  const std::vector<Block> bs = blocks(mesh);
  size_t total = 0;
  for (const Block& b : bs) total += b.nodes.size();
  appendInt(&out, static_cast<long long>(total));
  out.push_back('\n');
  long long tag = 1;
  for (const Block& b : bs)
    for (size_t i = 0; i < b.nodes.size(); ++i) {
      out += std::to_string(tag++) + " " + std::to_string(b.type) + " 2 " + std::to_string(b.ref) + " " +
             std::to_string(b.ref);
      appendElementNodes(&out, b, i);
    }
  out += "$EndElements\n";
  return out;
}

std::string writeV41(const Mesh& mesh) {
  const std::vector<Block> bs = blocks(mesh);
  // One entity per (dimension, ref); its tag is its rank among that dimension's refs.
  std::map<std::pair<int, int>, int> entity;
  std::vector<int> perDim(3, 0);
  for (const Block& b : bs)
    if (entity.emplace(std::make_pair(b.dim, b.ref), perDim[b.dim] + 1).second) ++perDim[b.dim];
  const bool noSurface = perDim[2] == 0;
  if (noSurface) perDim[2] = 1;  // the nodes need an entity: an untagged surface
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  if (!mesh.points.empty()) {
    lo = hi = mesh.points[0];
    for (const Vec3& p : mesh.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  std::string box;
  for (const Vec3* v : {&lo, &hi}) {
    for (int k = 0; k < 3; ++k) {
      box.push_back(' ');
      io_detail::appendNumber(&box, (*v)[k]);
    }
  }
  std::string out = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 ";
  out += std::to_string(perDim[1]) + " " + std::to_string(perDim[2]) + " 0\n";
  for (const auto& [key, tag] : entity)
    if (key.first == 1) out += std::to_string(tag) + box + " 1 " + std::to_string(key.second) + " 0\n";
  for (const auto& [key, tag] : entity)
    if (key.first == 2) out += std::to_string(tag) + box + " 1 " + std::to_string(key.second) + " 0\n";
  if (noSurface) out += "1" + box + " 0 0\n";
  out += "$EndEntities\n$Nodes\n";
  const int n = mesh.vertexCount();
  out += "1 " + std::to_string(n) + " " + std::to_string(n > 0 ? 1 : 0) + " " + std::to_string(n) + "\n";
  out += "2 1 0 " + std::to_string(n) + "\n";
  for (int i = 0; i < n; ++i) {
    appendInt(&out, i + 1);
    out.push_back('\n');
  }
  for (const Vec3& p : mesh.points) appendXyzLine(&out, p);
  out += "$EndNodes\n$Elements\n";
  size_t total = 0;
  for (const Block& b : bs) total += b.nodes.size();
  out += std::to_string(bs.size()) + " " + std::to_string(total) + " " + std::to_string(total > 0 ? 1 : 0) + " " +
         std::to_string(total) + "\n";
  long long tag = 1;
  for (const Block& b : bs) {
    out += std::to_string(b.dim) + " " + std::to_string(entity.at({b.dim, b.ref})) + " " + std::to_string(b.type) +
           " " + std::to_string(b.nodes.size()) + "\n";
    for (size_t i = 0; i < b.nodes.size(); ++i) {
      appendInt(&out, tag++);
      appendElementNodes(&out, b, i);
    }
  }
  out += "$EndElements\n";
  return out;
}

// Reading: node tags are mapped to indices in order of appearance.
struct Reader {
  TokenStream ts;
  Mesh mesh;
  std::unordered_map<long long, int> index;

  explicit Reader(const std::string& text) : ts(text, "msh", 0) {}

  void expect(const std::string& key) {
    if (ts.atEnd() || ts.peek().str() != key) ts.fail("'" + key + "'");
    ts.next();
  }
  void skipSection(const std::string& name) {
    const std::string end = "$End" + name.substr(1);
    while (!ts.atEnd() && ts.peek().str() != end) ts.next();
    expect(end);
  }
  int node(long long tag) {
    const auto it = index.find(tag);
    if (it == index.end()) ts.fail("a node tag defined in $Nodes (" + std::to_string(tag) + " is not)");
    return it->second;
  }
  void addNode(long long tag, const Vec3& p) {
    if (!index.emplace(tag, mesh.vertexCount()).second)
      ts.fail("distinct node tags (" + std::to_string(tag) + " twice)");
    mesh.points.push_back(p);
    mesh.pointRefs.push_back(0);
  }
  Vec3 xyz() {
    const double x = ts.number("x"), y = ts.number("y"), z = ts.number("z");
    return {x, y, z};
  }
  // One element of a Gmsh type with its nodes; false for skipped point elements.
  void addElement(int type, int ref) {
    const int arity = type == 1 ? 2 : type == 2 ? 3 : type == 3 ? 4 : type == 15 ? 1 : 0;
    if (arity == 0)
      ts.failAt(ts.line(),
                "element type " + std::to_string(type) + " is not supported (1 line, 2 triangle, 3 quad, 15 point)");
    int v[4];
    for (int k = 0; k < arity; ++k) v[k] = node(ts.integer("a node tag"));
    if (type == 1) {
      mesh.edges.push_back({v[0], v[1]});
      mesh.edgeRefs.push_back(ref);
    } else if (type == 2) {
      mesh.triangles.push_back({v[0], v[1], v[2]});
      mesh.triangleRefs.push_back(ref);
    } else if (type == 3) {
      mesh.quads.push_back({v[0], v[1], v[2], v[3]});
      mesh.quadRefs.push_back(ref);
    }
  }
};

void readV22(Reader& r) {
  while (!r.ts.atEnd()) {
    const std::string section = r.ts.next().str();
    if (section == "$Nodes") {
      const long long n = r.ts.count("the number of nodes", 4);
      for (long long i = 0; i < n; ++i) {
        const long long tag = r.ts.integer("a node tag");
        r.addNode(tag, r.xyz());
      }
      r.expect("$EndNodes");
    } else if (section == "$Elements") {
      const long long n = r.ts.count("the number of elements", 4);
      for (long long i = 0; i < n; ++i) {
        r.ts.integer("an element tag");
        const int type = static_cast<int>(r.ts.integer("an element type"));
        const long long tags = r.ts.count("the number of tags", 1);
        int ref = 0;
        for (long long k = 0; k < tags; ++k) {
          const long long t = r.ts.integer("a tag");
          if (k == 0) ref = static_cast<int>(t);
        }
        r.addElement(type, ref);
      }
      r.expect("$EndElements");
    } else if (!section.empty() && section[0] == '$') {
      r.skipSection(section);
    } else {
      r.ts.failAt(r.ts.line(), "expected a section ($Nodes, $Elements, ...), got '" + section + "'");
    }
  }
}

void readV41(Reader& r) {
  std::map<std::pair<int, long long>, int> physical;  // (dim, entity tag) -> first physical tag
  while (!r.ts.atEnd()) {
    const std::string section = r.ts.next().str();
    if (section == "$Entities") {
      long long count[4];
      for (long long& c : count) c = r.ts.count("an entity count", 2);
      for (int dim = 0; dim < 4; ++dim)
        for (long long i = 0; i < count[dim]; ++i) {
          const long long tag = r.ts.integer("an entity tag");
          for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) r.ts.number("a coordinate");
          const long long np = r.ts.count("the number of physical tags", 1);
          int ref = 0;
          for (long long k = 0; k < np; ++k) {
            const long long t = r.ts.integer("a physical tag");
            if (k == 0) ref = static_cast<int>(t);
          }
          physical[{dim, tag}] = ref;
          if (dim > 0) {
            const long long nb = r.ts.count("the number of bounding entities", 1);
            for (long long k = 0; k < nb; ++k) r.ts.integer("a bounding entity tag");
          }
        }
      r.expect("$EndEntities");
    } else if (section == "$Nodes") {
      const long long blocks = r.ts.count("the number of node blocks", 4);
      r.ts.count("the number of nodes", 4);
      r.ts.integer("the smallest node tag");
      r.ts.integer("the largest node tag");
      for (long long b = 0; b < blocks; ++b) {
        r.ts.integer("an entity dimension");
        r.ts.integer("an entity tag");
        const long long parametric = r.ts.integer("parametric (0 or 1)");
        if (parametric != 0) r.ts.failAt(r.ts.line(), "parametric node blocks are not supported");
        const long long n = r.ts.count("the number of nodes in the block", 4);
        std::vector<long long> tags(static_cast<size_t>(n));
        for (long long& t : tags) t = r.ts.integer("a node tag");
        for (long long t : tags) r.addNode(t, r.xyz());
      }
      r.expect("$EndNodes");
    } else if (section == "$Elements") {
      const long long blocks = r.ts.count("the number of element blocks", 4);
      r.ts.count("the number of elements", 2);
      r.ts.integer("the smallest element tag");
      r.ts.integer("the largest element tag");
      for (long long b = 0; b < blocks; ++b) {
        const int dim = static_cast<int>(r.ts.integer("an entity dimension"));
        const long long entity = r.ts.integer("an entity tag");
        const int type = static_cast<int>(r.ts.integer("an element type"));
        const long long n = r.ts.count("the number of elements in the block", 2);
        const auto it = physical.find({dim, entity});
        const int ref = it == physical.end() ? 0 : it->second;
        for (long long i = 0; i < n; ++i) {
          r.ts.integer("an element tag");
          r.addElement(type, ref);
        }
      }
      r.expect("$EndElements");
    } else if (!section.empty() && section[0] == '$') {
      r.skipSection(section);
    } else {
      r.ts.failAt(r.ts.line(), "expected a section ($Nodes, $Elements, ...), got '" + section + "'");
    }
  }
}

}  // namespace

std::string writeGmsh(const Mesh& mesh, GmshVersion version) {
  return version == GmshVersion::V22 ? writeV22(mesh) : writeV41(mesh);
}

Mesh parseGmsh(const std::string& text) {
  Reader r(text);
  r.expect("$MeshFormat");
  const int line = r.ts.line();
  const std::string version = r.ts.next().str();
  const long long fileType = r.ts.integer("the file type (0: ASCII)");
  r.ts.integer("the data size");
  if (fileType != 0)
    r.ts.failAt(line, "binary .msh files are not supported (write ASCII: gmsh -format msh41 or -bin 0)");
  r.expect("$EndMeshFormat");
  if (version == "2.2" || version == "2.1" || version == "2")
    readV22(r);
  else if (version == "4.1")
    readV41(r);
  else
    r.ts.failAt(line, "expected version 4.1 or 2.2, got '" + version + "'");
  Mesh& m = r.mesh;
  m.dimension = 2;
  for (const Vec3& p : m.points)
    if (p.z() != 0.0) m.dimension = 3;
  return std::move(m);
}

}  // namespace anisomesh

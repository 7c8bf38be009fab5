#pragma once
// Private: the sections BAMG (FreeFem's ffbamg) adds to the .mesh files it writes, skipped
// by the Medit reader so that BAMG's output reads as a mesh: quoted strings (Identifier,
// Geometry, MeshSupportOfVertices, IdentityOfMeshSupport) and counted tables of integers
// and parameters (VertexOnGeometricVertex, SubDomainFromMesh, ...).
#include <map>
#include <string>

#include "tokens.h"

namespace anisomesh {
namespace io_detail {

// Skips the section named key when it is one of BAMG's and returns true; false otherwise.
inline bool skipBamgSection(TokenStream& ts, const std::string& key) {
  static const std::map<std::string, int> tables{{"SubDomain", 4},
                                                 {"SubDomainFromMesh", 4},
                                                 {"SubDomainFromGeom", 4},
                                                 {"VertexOnGeometricVertex", 2},
                                                 {"VertexOnGeometricEdge", 3},
                                                 {"EdgeOnGeometricEdge", 2},
                                                 {"VertexOnSupportVertex", 2},
                                                 {"VertexOnSupportEdge", 3},
                                                 {"VertexOnSupportTriangle", 4},
                                                 {"CrackedEdges", 4}};
  if (key == "Identifier" || key == "Geometry" || key == "MeshSupportOfVertices" || key == "IdentityOfMeshSupport") {
    // One double-quoted string, possibly with blanks (so several tokens).
    if (ts.atEnd() || ts.peek().size == 0 || ts.peek().begin[0] != '"') ts.fail("a quoted string after " + key);
    std::string t = ts.next().str();
    while (t.size() < 2 || t.back() != '"') t = ts.next().str();
    return true;
  }
  const auto it = tables.find(key);
  if (it == tables.end()) return false;
  const long long n = ts.count("the number of " + key, it->second);
  for (long long i = 0; i < n * it->second; ++i) ts.number("a value of " + key);
  return true;
}

}  // namespace io_detail
}  // namespace anisomesh

#pragma once
// Gmsh .msh ASCII meshes, versions 4.1 and 2.2: vertices, boundary edges (lines), triangles
// and quads, each element's reference as its physical tag (4.1: one entity per dimension
// and reference, the reference as the entity's physical tag; 2.2: tags "ref ref").
// Vertex references and parameter coordinates are not carried.
#include <string>

#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

enum class GmshVersion { V41, V22 };

// The mesh as .msh text (numbers round-trip exactly; node and element tags from 1).
std::string writeGmsh(const Mesh& mesh, GmshVersion version = GmshVersion::V41);

// Parses .msh ASCII text of version 4.1 or 2.2 (point elements and unknown sections
// skipped); ParseError naming the line otherwise (binary files, other element types).
// Dimension 2 when every z is 0.
Mesh parseGmsh(const std::string& text);

}  // namespace anisomesh

#pragma once
// Binary Medit formats (.meshb, .solb) as libMeshb and MMG read and write them: an int32
// code 1 (its byte order gives the file's endianness), an int32 version (1: float reals,
// 2: double reals, 3: also 64-bit keyword positions, 4: also 64-bit integers), then
// keywords, each an int32 code, the position of the next keyword and its data.
#include <string>

#include "anisomesh/io/medit.h"
#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

// The mesh as a .meshb file (little-endian, version 2, or 3 when above 2 GiB): Dimension,
// Vertices, Edges, Triangles, Quadrilaterals with references, End.
std::string writeMeditBinary(const Mesh& mesh);

// Parses .meshb bytes of version 1 to 4 in either byte order (Corners, Ridges,
// RequiredVertices and other keywords skipped); throws ParseError naming the keyword and
// the byte offset: counts larger than the bytes left, indices out of range, references
// beyond 32 bits, a missing End.
Mesh parseMeditBinary(const std::string& bytes);

// The solution as a .solb file (little-endian, version 2): SolAtVertices with one field.
std::string writeSolBinary(const SolData& sol);

// Parses .solb bytes (one SolAtVertices field of type 1, 2 or 3); ParseError as above.
SolData parseSolBinary(const std::string& bytes);

}  // namespace anisomesh

#pragma once
// Other mesh formats (VTK legacy ASCII, Wavefront OBJ) and format dispatch by file
// extension. String-based variants exist for every format.
#include <string>

#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

// Gmsh: .msh 4.1 (written for the .msh extension); Gmsh22: .msh 2.2 (read: either);
// MeditBinary: .meshb (medit_binary.h). The strings of the binary format hold bytes.
enum class MeshFormat { Medit, Vtk, Obj, Gmsh, Gmsh22, MeditBinary };

// The format of a path by its extension (.mesh, .meshb, .vtk, .obj, .msh); InvalidArgument otherwise.
MeshFormat meshFormatFromPath(const std::string& path);

// VTK legacy ASCII UNSTRUCTURED_GRID: lines (edges), triangles and quads, with the
// references as integer cell data "ref".
std::string writeVtk(const Mesh& mesh);

// Parses what writeVtk writes (POINTS, CELLS, CELL_TYPES 3/5/9, optional CELL_DATA
// SCALARS); ParseError naming the line otherwise. Dimension 2 when every z is 0.
Mesh parseVtk(const std::string& text);

// Wavefront OBJ: "v x y z", "f" (1-based, triangles and quads), "l" for edges; no refs.
std::string writeObj(const Mesh& mesh);

// Parses OBJ v / f / l statements (other statements ignored; "i/j/k" and negative
// indices accepted); ParseError naming the line. Dimension 2 when every z is 0.
Mesh parseObj(const std::string& text);

// The mesh in the given format.
std::string writeMeshString(const Mesh& mesh, MeshFormat format);

// Parses text in the given format.
Mesh parseMeshString(const std::string& text, MeshFormat format);

// Writes mesh to path atomically, in the format of its extension.
void writeMeshFile(const std::string& path, const Mesh& mesh);

// Reads a mesh file in the format of its extension.
Mesh readMeshFile(const std::string& path);

}  // namespace anisomesh

#pragma once
// Medit ASCII formats: meshes (.mesh) and per-vertex solutions (.sol). String-based
// variants exist for every operation (the browser has no file system).
#include <string>
#include <vector>

#include "anisomesh/mesh/mesh.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

// Medit .mesh text (MeshVersionFormatted 2, Dimension mesh.dimension, Vertices, Edges,
// Triangles, Quadrilaterals with references, End); numbers round-trip exactly.
std::string writeMedit(const Mesh& mesh);

// Parses Medit .mesh text (version 1 or 2, dimension 2 or 3, '#' comments); throws
// ParseError naming the line and what was expected.
Mesh parseMedit(const std::string& text);

// Reads a .mesh file (IoError when unreadable, ParseError when malformed).
Mesh readMeditFile(const std::string& path);

// Writes a .mesh file atomically.
void writeMeditFile(const std::string& path, const Mesh& mesh);

// A Medit solution at vertices holding one field: type 1 (scalar), 2 (vector, one value
// per dimension) or 3 (symmetric tensor, m11 m12 m22 in 2D; m11 m12 m22 m13 m23 m33 in 3D).
struct SolData {
  int dimension = 2;
  int type = 1;
  std::vector<double> values;  // count() * valuesPerVertex() entries
  // Number of values per vertex for this type and dimension.
  int valuesPerVertex() const { return type == 1 ? 1 : type == 2 ? dimension : (dimension == 2 ? 3 : 6); }
  // Number of vertices the solution covers.
  int count() const { return static_cast<int>(values.size()) / valuesPerVertex(); }
};

// Medit .sol text (SolAtVertices, one field).
std::string writeSol(const SolData& sol);

// Parses Medit .sol text; ParseError on malformed text, unsupported types or several fields.
SolData parseSol(const std::string& text);

// Reads a .sol file, or a binary .solb file by its extension (IoError when unreadable,
// ParseError when malformed).
SolData readSolFile(const std::string& path);

// Writes a .sol file (a .solb file by its extension) atomically.
void writeSolFile(const std::string& path, const SolData& sol);

// Per-vertex metrics of a 2D solution: a scalar is a size h (isotropic metric h), a tensor
// is M. Throws ParseError naming both counts when the solution does not have
// vertexCount entries, InvalidMetric on a bad value (naming the vertex).
std::vector<Metric> solToMetrics(const SolData& sol, int vertexCount);

// A 2D tensor (type 3) solution holding the given metrics.
SolData metricsToSol(const std::vector<Metric>& metrics);

}  // namespace anisomesh

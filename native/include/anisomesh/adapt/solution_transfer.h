#pragma once
// Solution transfer: P1 interpolation of fields from one planar triangulation onto the
// vertices of another, by point location in the old mesh (a uniform grid of its triangles,
// about one triangle per cell). A point inside (or on) a triangle takes the barycentric
// combination of its three values, so linear fields are reproduced exactly (up to
// rounding). A point outside the old mesh (a remeshed curved boundary cuts corners the
// other way, or rounding) takes the value at the nearest point of the old mesh: the
// barycentric coordinates of the nearest triangle clamped to it (documented; no
// extrapolation).
#include <array>
#include <vector>

#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

// Point location in a planar triangulation.
class TriangleLocator {
 public:
  // Takes the triangles (and split quads) of mesh. Throws InvalidArgument without triangles.
  explicit TriangleLocator(const Mesh& mesh);
  // The triangle containing p (or nearest to it) and p's barycentric coordinates in it,
  // clamped to the triangle when p is outside; *inside says which case it was.
  int locate(const Vec2& p, std::array<double, 3>* bary, bool* inside = nullptr) const;
  // Vertices of triangle t.
  const std::array<int, 3>& triangle(int t) const { return tris_[size_t(t)]; }

 private:
  int cellIndex(int x, int y) const { return y * nx_ + x; }
  std::vector<Vec2> pts_;
  std::vector<std::array<int, 3>> tris_;
  Vec2 lo_{0, 0};
  int nx_ = 1, ny_ = 1;
  Vec2 cell_{1, 1};
  std::vector<int> cellStart_, cellTris_;  // CSR: triangles overlapping each cell's box
};

// Each field (one value per vertex of from) interpolated at the vertices of to. Throws
// InvalidArgument on a count mismatch or a non-finite value (validateField).
std::vector<std::vector<double>> transferFields(const Mesh& from, const std::vector<std::vector<double>>& fields,
                                                const Mesh& to);

}  // namespace anisomesh

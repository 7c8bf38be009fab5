#pragma once
// A piecewise-linear metric field over a triangulation (per-vertex metrics, barycentric
// interpolation of Mt), with a uniform grid for point location. Remeshing evaluates it
// as the continuous source of its background-mesh control space (pipeline.h).
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

class TriangleMeshMetricField : public ControlSpace {
 public:
  // metrics[i] belongs to mesh.points[i]; quads are split into two triangles. Throws
  // InvalidArgument when the counts differ or the mesh has no triangle or quad,
  // InvalidDomain for a vertex with a non-finite coordinate.
  TriangleMeshMetricField(const Mesh& mesh, std::vector<Metric> metrics);
  // Barycentric interpolation of Mt in the containing triangle; outside the mesh, the
  // nearest triangle found in the grid with its coordinates clamped to it.
  Metric metricAt(const Vec2& p) const override;
  Box2 bounds() const override { return box_; }
  // True when b meets a grid cell holding a triangle (outside, the field is only extrapolated).
  bool meets(const Box2& b) const;

 private:
  int cellIndex(int x, int y) const { return y * nx_ + x; }
  std::vector<Vec2> pts_;
  std::vector<std::array<int, 3>> tris_;
  std::vector<Metric> metrics_;
  Box2 box_;
  int nx_ = 1, ny_ = 1;
  Vec2 cell_{1, 1};
  std::vector<int> cellStart_;  // CSR: triangles of cell c are cellTris_[cellStart_[c] .. cellStart_[c + 1])
  std::vector<int> cellTris_;
  std::vector<int> coveredSum_;  // (nx + 1) x (ny + 1) summed-area table of the nonempty cells
  std::vector<int> emptyRings_;  // per cell: Chebyshev distance (cells) to the nearest nonempty cell
};

}  // namespace anisomesh

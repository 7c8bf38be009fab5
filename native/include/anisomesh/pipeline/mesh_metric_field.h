#pragma once
// A piecewise-linear metric field over a triangulation (per-vertex metrics, barycentric
// interpolation of Mt), with a uniform grid for point location. Remeshing evaluates it
// as the continuous source of its background-mesh control space (pipeline.h).
//
// The field reads the mesh's points and triangles in place (no copy: a 3.4M-triangle
// carrier would cost 70 MB more), so the mesh must outlive it; a temporary mesh is
// refused at compile time. The metrics are read in place too when given as an lvalue
// (they must then outlive the field), or moved into the field when given as an rvalue.
#include <array>
#include <cstdint>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

class TriangleMeshMetricField : public ControlSpace {
 public:
  // metrics[i] belongs to mesh.points[i]; quads are split into two triangles. Throws
  // InvalidArgument when the counts differ or the mesh has no triangle or quad,
  // InvalidDomain for a vertex with a non-finite coordinate.
  TriangleMeshMetricField(const Mesh& mesh, const std::vector<Metric>& metrics);
  TriangleMeshMetricField(const Mesh& mesh, std::vector<Metric>&& metrics);
  TriangleMeshMetricField(Mesh&& mesh, const std::vector<Metric>& metrics) = delete;
  TriangleMeshMetricField(Mesh&& mesh, std::vector<Metric>&& metrics) = delete;
  TriangleMeshMetricField(const TriangleMeshMetricField&) = delete;
  TriangleMeshMetricField& operator=(const TriangleMeshMetricField&) = delete;
  // Barycentric interpolation of Mt in the containing triangle; outside the mesh, the
  // nearest triangle (exact: of equal distances the lowest index) with its coordinates
  // clamped to it. The grid's cell size changes the speed only, not the answer.
  Metric metricAt(const Vec2& p) const override;
  Box2 bounds() const override { return box_; }
  // True when b meets a grid cell holding a triangle (outside, the field is only extrapolated).
  bool meets(const Box2& b) const;

 private:
  void build(const Mesh& mesh);
  int cellIndex(int x, int y) const { return y * nx_ + x; }
  Vec2 point(int v) const { return pts_[v].head<2>(); }
  const Vec3* pts_ = nullptr;                 // the mesh's points (read in place)
  const std::array<int, 3>* tris_ = nullptr;  // the mesh's triangles, or splitTris_
  size_t triCount_ = 0;
  std::vector<std::array<int, 3>> splitTris_;  // triangles + quads split in two (meshes with quads only)
  std::vector<Metric> ownedMetrics_;           // the metrics when moved in
  const Metric* metrics_ = nullptr;
  Box2 box_;
  int nx_ = 1, ny_ = 1;
  Vec2 cell_{1, 1};
  std::vector<int> cellStart_;  // CSR: triangles of cell c are cellTris_[cellStart_[c] .. cellStart_[c + 1])
  std::vector<int> cellTris_;
  // Per entry of cellTris_ (and 3 more: metricAt reads four at a time): the sub-cells (4
  // bits each: x0, x1, y0, y1 of a 16 x 16 grid of the cell) its triangle's box, widened
  // by a margin far above the containment tolerance, meets; a triangle skipped for it
  // cannot contain the query point. A graded or anisotropic carrier lists hundreds of
  // triangles in its fine cells, few of them near p.
  std::vector<std::uint16_t> cellFilter_;
  Vec2 subScale_{1, 1};  // filter grid cells per unit length (multiplied: only monotonicity matters)
  Vec2 cellOrigin(int x, int y) const { return Vec2(box_.lo.x() + x * cell_.x(), box_.lo.y() + y * cell_.y()); }
  std::vector<int> coveredSum_;            // (nx + 1) x (ny + 1) summed-area table of the nonempty cells
  std::vector<std::uint16_t> emptyRings_;  // per cell: Chebyshev distance (cells, <= 4098) to the nearest nonempty cell
};

}  // namespace anisomesh

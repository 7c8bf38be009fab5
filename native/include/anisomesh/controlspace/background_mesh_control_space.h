#pragma once
// Background mesh control space (section 2.1, fig. 1b; interpolation section 4.2, eq. 11).
// A conforming triangulation of the control nodes: the main-level grid of the box, each
// cell split into two triangles, refined by longest-edge bisection (Rivara's LEPP), which
// keeps the triangulation conforming and the angles bounded. A query finds the containing
// triangle by walking from a triangle picked by an auxiliary uniform grid, then
// interpolates from V* = the triangle's three vertices with inverse squared distance
// weights (eq. 11), taking a vertex's metric directly within epsilon of it. The choice
// of V* = 3 vertices keeps the query short; a linear (barycentric) option gives a
// continuous field when that matters (e.g. exact minima of nested meshes).
//
// Threads: metricAt/mtAt/locate* only read, so concurrent queries are safe; building
// operations (refine, set*, the algorithms) need exclusive access.
#include <array>
#include <optional>
#include <vector>

#include "anisomesh/controlspace/adaptive_control_space.h"

namespace anisomesh {

enum class BackgroundInterpolation {
  InverseSquaredDistance,  // eq. 11 over the containing triangle's vertices
  Linear,                  // barycentric weights (continuous, exact for linear Mt fields)
};

struct BackgroundMeshOptions {
  int initialGrid = 4;  // main-level grid cells per side (each cell -> 2 triangles)
  int maxLevel = 14;    // smallest element: longest initial edge / 2^maxLevel
  BackgroundInterpolation interpolation = BackgroundInterpolation::InverseSquaredDistance;
  double epsilon = 1e-12;               // relative to the box diagonal: "at a vertex" distance
  std::optional<Metric> initialMetric;  // as in QuadtreeOptions
};

class BackgroundMeshControlSpace : public AdaptiveControlSpace {
 public:
  // Triangulates the main-level grid of box. Throws InvalidDomain for an empty, inverted
  // or non-finite box, InvalidArgument for options out of range.
  explicit BackgroundMeshControlSpace(const Box2& box, const BackgroundMeshOptions& options = {});

  // Interpolated metric (eq. 11); points outside the box are clamped onto it.
  Metric metricAt(const Vec2& p) const override;
  // metricAt(p), the walk started from the triangle in hint (then set to p's triangle).
  Metric metricAtNear(const Vec2& p, int& hint) const override;
  // Interpolated Mt entries at p (the allocation-free core of metricAt).
  SymMt mtAt(const Vec2& p) const;
  InterpolationStencil stencilAt(const Vec2& p) const override;
  // Linear interpolation (continuous): interpolated in e's own triangle, which holds its
  // samples (the centroid inside, the edge midpoints on its sides), with no walk; the other
  // interpolation differs across edges, so it locates the point as metricAt does.
  Metric elementSampleMetric(const ControlElement& e, int k) const override;
  // Triangle containing p (clamped onto the box), by walking.
  int locateTriangle(const Vec2& p) const;
  // True when p lies in the closed triangle t.
  bool triangleContains(int t, const Vec2& p) const;

  std::vector<std::array<int, 2>> rawEdges(bool structure) const override;
  int elementCount() const override { return static_cast<int>(tri_.size()); }
  std::vector<std::vector<int>> elementNodes() const override;
  void refine(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) override;
  void refineConcurrently(const ElementPredicate& pred, const NewNodesCallback& onNewNodes) override;
  std::vector<double> nodeElementSizes() const override;
  double minElementSize() const override { return minSize_; }
  const char* kindName() const override { return "background"; }
  std::unique_ptr<AdaptiveControlSpace> clone() const override {
    return std::make_unique<BackgroundMeshControlSpace>(*this);
  }

  // Bisects triangle t by its longest edge (splitting neighbours first as LEPP requires).
  void bisect(int t);
  // Vertices (counter-clockwise) and edge neighbours (across the edge opposite vertex k,
  // -1 on the boundary) of triangle t.
  const std::array<int, 3>& triangle(int t) const { return tri_[t]; }
  const std::array<int, 3>& neighbours(int t) const { return nbr_[t]; }
  BackgroundInterpolation interpolation() const { return options_.interpolation; }
  // Number of bytes held by the structure.
  size_t memoryBytes() const;

 private:
  int longestEdge(int t) const;
  double edgeKey(int a, int b) const;
  void splitPair(int t, int i);
  void bisectImpl(int t);
  void rebuildLocator();
  void refineImpl(const ElementPredicate& pred, const NewNodesCallback& onNewNodes, bool readOnly);
  ControlElement elementOf(int t) const;
  double orient(int a, int b, const Vec2& p) const;
  SymMt mtIn(int t, const Vec2& q) const;        // Mt interpolated in triangle t at q (in the box)
  SymMt weighted(int t, const double* w) const;  // sum of w[k] Mt(v[k]) / sum of w[k]
  // locateTriangle(q) for q in the box, walking from triangle `from` (a few steps): the
  // triangle when the walk ends with q clearly inside it (o: its three orient() values),
  // else -1.
  int locateTriangleFrom(const Vec2& q, int from, double* o) const;
  Vec2 clampedToBox(const Vec2& p) const;  // p clamped onto the box; a non-finite p: its corner

  BackgroundMeshOptions options_;
  double minSize_ = 0.0;
  double eps2_ = 0.0;
  double margin2_ = 0.0;  // locateTriangleFrom: (distance p keeps from the edges' lines)^2
  std::vector<std::array<int, 3>> tri_;
  std::vector<std::array<int, 3>> nbr_;
  std::vector<int> touched_;  // triangles changed by the current refinement batch
  std::vector<char> touchedFlag_;
  // Auxiliary grid: a triangle containing each grid cell's centre.
  int gridSide_ = 1;
  Vec2 gridInv_;
  std::vector<int> grid_;
  // True between a refine() batch and the next query (or refine()'s end): the grid is
  // rebuilt lazily, so batches nobody queries in do not pay for it.
  mutable bool locatorStale_ = false;
};

}  // namespace anisomesh

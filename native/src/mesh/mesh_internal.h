#pragma once
// Internal helpers of the mesh area shared by the mesher, the quad conversion and the
// quality report: the metric element qualities and the quad conversion.
#include <cmath>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/core/types.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"
#include "anisomesh/metric/sym_mt.h"

namespace anisomesh {

// Q = 4 sqrt(3) A_M / sum l_M^2 under the constant metric m: 1 for the equilateral
// triangle in metric space, 0 when flat, negative when clockwise.
inline double metricTriangleQuality(const SymMt& m, const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 e1 = m.apply(b - a), e2 = m.apply(c - b), e3 = m.apply(a - c);
  const double cross = e1.x() * (-e3.y()) - e1.y() * (-e3.x());  // 2 A_M
  const double sum = e1.squaredNorm() + e2.squaredNorm() + e3.squaredNorm();
  return sum > 0.0 ? 2.0 * std::sqrt(3.0) * cross / sum : 0.0;
}

// Quad quality under the constant metric m: the minimum over the four corners of
// 2 |e1 x e2| / (|e1|^2 + |e2|^2), signed; 1 for a square in metric space, <= 0 when a
// corner is reflex or the quad is inverted.
inline double metricQuadQuality(const SymMt& m, const Vec2* p) {
  double q = 1.0;
  for (int k = 0; k < 4; ++k) {
    const Vec2 e1 = m.apply(p[(k + 1) % 4] - p[k]), e2 = m.apply(p[(k + 3) % 4] - p[k]);
    const double cross = e1.x() * e2.y() - e1.y() * e2.x();
    const double sum = e1.squaredNorm() + e2.squaredNorm();
    q = std::min(q, sum > 0.0 ? 2.0 * cross / sum : 0.0);
  }
  return q;
}

// Quad-dominant conversion (greedy merge of triangle pairs by metric quad quality, pairs
// below minQuadQuality kept as triangles). vertexMt holds Mt per vertex.
void convertToQuads(Mesh& mesh, const std::vector<SymMt>& vertexMt, double minQuadQuality);

// Swaps and polish rounds on the triangles around the cut vertices [seamBegin, seamEnd) of a
// decomposed domain's merged mesh, which neither part could move (planar/seam_polish.cpp).
void polishDecompositionSeams(Mesh& merged, int seamBegin, int seamEnd, const ControlSpace& cs,
                              const PlanarMesherOptions& options);

}  // namespace anisomesh

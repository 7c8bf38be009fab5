#pragma once
// Recovery of the gradient and Hessian of a P1 field given at the vertices of a planar
// triangulation, by a least-squares quadratic fit on vertex patches (Zhang and Naga's
// polynomial preserving recovery in its vertex form): at vertex i the quadratic
//   q(x) = f_i + g . (x - x_i) + 1/2 (x - x_i)^T H (x - x_i)
// interpolating f_i minimizes sum_j (q(x_j) - f_j)^2 over the patch's vertices j, with
// offsets normalized by the patch's covariance (conditioning independent of the patch's size
// and anisotropy). Patch: the 1-ring for interior
// vertices, the 2-ring for boundary vertices (a one-sided patch large enough that the fit
// is exact for quadratics and consistent, so the boundary does not degrade to zero or
// noise); a patch whose fit is singular or ill-conditioned grows by one ring (up to maxRings).
// Exact (up to rounding) for quadratic fields on any mesh; for smooth fields the Hessian
// error is O(h) on unstructured meshes (O(h^2) on symmetric patches).
#include <vector>

#include "anisomesh/core/types.h"
#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

struct HessianRecoveryOptions {
  int interiorRings = 1;  // rings of the patch of an interior vertex (>= 1)
  int boundaryRings = 2;  // rings of the patch of a boundary vertex (>= 1)
  int maxRings = 8;       // largest patch tried when a fit is ill-conditioned
};

// Recovered derivatives at every vertex, plus an estimate of the rounding noise of each
// Hessian (entries below it carry no information: linear fields recover about this).
struct RecoveredDerivatives {
  std::vector<Vec2> gradient;
  std::vector<Mat2> hessian;
  std::vector<double> hessianNoise;  // 1e3 * machine epsilon * max |f| on the patch / (patch spread)^2
};

// Checks the input of recovery and adaptation: the mesh is planar with triangles (quads are
// split in two), no element is inverted or flat, the field has one finite value per vertex.
// Throws InvalidArgument (count mismatch, NaN/infinite value naming the vertex, no
// triangles) or InvalidDomain (an inverted or zero-area element, naming it).
void validateField(const Mesh& mesh, const std::vector<double>& field);

// The triangles of the mesh (quads split along their 0-2 diagonal), in element order.
std::vector<std::array<int, 3>> meshTriangles(const Mesh& mesh);

// Gradient and Hessian at every vertex of mesh of the P1 field (validated by validateField).
// Throws InvalidArgument when a vertex's patch cannot determine a quadratic even at maxRings
// (e.g. every vertex near it on one line), naming the vertex.
RecoveredDerivatives recoverHessian(const Mesh& mesh, const std::vector<double>& field,
                                    const HessianRecoveryOptions& options = {});

}  // namespace anisomesh

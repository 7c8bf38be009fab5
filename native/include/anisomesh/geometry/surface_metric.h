#pragma once
// The metric a surface patch requests (paper sections 3.1 and 4.3): sizes from the
// principal curvatures in 3D, mapped into the parameter plane where the patch is
// meshed, plus the parameterization matrix Mp and 3D measures for quality reports.
//
// Sizes along a principal direction with curvature k (chord tolerance tol, absolute,
// in model units): an arc of radius 1/|k| spanned by a chord of length h deviates from
// it by the sagitta s ~ |k| h^2 / 8, so h = sqrt(8 tol / |k|). With an angle tolerance
// a (radians) the chord may turn the tangent by at most a: h = a / |k|. The smaller
// one wins (a chord tolerance relative to the radius of curvature, tol = t / |k|, is
// the angle criterion with a = sqrt(8 t)). Then h is clamped to [hmin, hmax] and the
// larger of the two sizes is capped at maxAspectRatio times the smaller (the paper's d_max).
// The surface mesher divides the tolerance by chordSafety^2 (default 8/3, see
// kDefaultChordSafety in surface_mesh.h) so edges up to metric length sqrt2 and triangle
// interiors stay within it.
//
// Mapping into (u, v): a 3D tangent metric M3 pulls back through J = [Su Sv] as
// M_uv = J^T M3 J, so the metric length of a parameter vector du equals the M3 length
// of its 3D image J du (for an isotropic size h, M_uv = G / h^2).
#include <algorithm>
#include <functional>
#include <memory>
#include <optional>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/geometry/surface.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

struct SurfaceMetricOptions {
  // Largest distance between an edge (chord) and the surface, absolute in model units;
  // <= 0 disables the chord criterion.
  double chordTolerance = 0.01;
  // Largest turn of the surface tangent along one edge, in radians; <= 0 disables it.
  double angleTolerance = 0.0;
  // Smallest and largest requested edge length in 3D (0 < hmin <= hmax).
  double hmin = 1e-3;
  double hmax = 1.0;
  // d_max: largest ratio of the two requested sizes (>= 1).
  double maxAspectRatio = 10.0;
};

// Throws InvalidArgument unless the options are usable (finite, 0 < hmin <= hmax, d_max >= 1).
void validate(const SurfaceMetricOptions& options);

// Requested edge length along a principal direction of curvature k, before the aspect cap.
double curvatureSize(double k, const SurfaceMetricOptions& options);

// A 3D metric at a surface point in its orthonormal frame (dir1, dir2, normal):
// sizes h1, h2 along the tangent directions and hn along the normal, so that chords
// (which leave the tangent plane a little) have a finite length. hn = min(h1, h2).
struct TangentMetric {
  Vec3 dir1 = Vec3::UnitX(), dir2 = Vec3::UnitY(), normal = Vec3::UnitZ();
  double h1 = 1.0, h2 = 1.0, hn = 1.0;
  // M3 = sum_i e_i e_i^T / h_i^2 (3x3 SPD).
  Mat3 tensor() const;
  // Its symmetric square root sum_i e_i e_i^T / h_i: |transform() x| is the metric length of x.
  Mat3 transform() const;
  // The restriction to the tangent plane as a 2x2 metric in the basis (dir1, dir2): diag(1/h1^2, 1/h2^2).
  Metric inTangentBasis() const { return Metric::fromSizes(0.0, h1, h2); }
};

// The requested 3D metric at uv from the principal curvatures; throws InvalidSurface at a degenerate point.
TangentMetric requestedMetric3D(const Surface& s, const Vec2& uv, const SurfaceMetricOptions& options);

// Pull-back of a 3D metric tensor into (u, v): J^T M3 J; throws InvalidMetric if the result is not SPD.
Metric pullBackMetric(const Mat3& m3, const SurfaceDerivatives& d);

// Pull-back of a tangent-plane metric given as a 2x2 metric in the orthonormal tangent
// basis (t1, t2): J^T B M B^T J with B = [t1 t2].
Metric pullBackTangentMetric(const Metric& m, const Vec3& t1, const Vec3& t2, const SurfaceDerivatives& d);

// The curvature metric in the parameter plane at uv (requestedMetric3D pulled back through J).
Metric parameterMetric(const Surface& s, const Vec2& uv, const SurfaceMetricOptions& options);

// Mp = sqrt(G) (symmetric square root of the first fundamental form): |Mp du| = |J du|,
// the 3D length of the parameter vector du (section 4.3).
Mat2 parameterizationMatrix(const Surface& s, const Vec2& uv);

// A user metric given in 3D: the tensor at a point of space (SPD 3x3).
using Metric3Function = std::function<Mat3(const Vec3&)>;

// The analytic control space of a patch: at each query the curvature metric, intersected
// with the optional user metrics (in (u, v) or in 3D); parameterizationAt() returns Mp.
// Queries are clamped into the surface domain. Degenerate points throw InvalidSurface;
// a sampling control space is expected to catch that and extrapolate (section 3.1).
class SurfaceCurvatureControlSpace : public ControlSpace {
 public:
  SurfaceCurvatureControlSpace(std::shared_ptr<const Surface> surface, const SurfaceMetricOptions& options);
  // Also intersect with a metric given in the parameter plane.
  void setUserMetric(MetricFunction f) { user2d_ = std::move(f); }
  // Also intersect with a metric given in 3D (pulled back through J).
  void setUserMetric3D(Metric3Function f) { user3d_ = std::move(f); }

  Metric metricAt(const Vec2& p) const override;
  // metricAt(p), or nothing where the curvature is unavailable (degenerate or non-finite
  // parameterization), for samplers that extrapolate there (section 3.1).
  std::optional<Metric> tryMetricAt(const Vec2& p) const;
  Mat2 parameterizationAt(const Vec2& p) const override;
  Box2 bounds() const override { return surface_->domain(); }

  const Surface& surface() const { return *surface_; }
  const SurfaceMetricOptions& options() const { return options_; }

 private:
  Vec2 clampToDomain(const Vec2& p) const;
  std::shared_ptr<const Surface> surface_;
  SurfaceMetricOptions options_;
  MetricFunction user2d_;
  Metric3Function user3d_;
};

// Metric length sqrt(x^T M3 x) of the segment pq under a constant 3D metric.
double edgeLength3D(const Vec3& p, const Vec3& q, const Mat3& m3);
// Length of the 3D chord S(a)S(b) in the requested 3D metric, Simpson-averaged over
// the metrics at a, the parameter midpoint and b.
double edgeLength3D(const Surface& s, const Vec2& a, const Vec2& b, const SurfaceMetricOptions& options);

// Q = 4 sqrt(3) A / (l1^2 + l2^2 + l3^2) of a 3D triangle in a constant 3D metric (1 for equilateral).
double triangleQuality3D(const Vec3& a, const Vec3& b, const Vec3& c, const Mat3& m3);
// Q of the triangle S(a)S(b)S(c), measured in the requested 3D metric at its parameter centroid.
double triangleQuality3D(const Surface& s, const Vec2& a, const Vec2& b, const Vec2& c,
                         const SurfaceMetricOptions& options);

struct ChordDeviationOptions {
  int samples = 32;  // interior sample points on the parameter segment (>= 1)
};

// Largest distance between the straight 3D segment S(a)S(b) and the surface curve
// S((1-t) a + t b), t in [0, 1], sampled at evenly spaced t.
double chordDeviation(const Surface& s, const Vec2& a, const Vec2& b, const ChordDeviationOptions& options = {});

// chordDeviation()'s gap at one sample: the distance from x to the segment pa + [0, 1] e
// (ee = |e|^2).
inline double chordGap(const Vec3& x, const Vec3& pa, const Vec3& e, double ee) {
  const double tau = ee > 0.0 ? std::min(std::max((x - pa).dot(e) / ee, 0.0), 1.0) : 0.0;
  return (x - (pa + tau * e)).norm();
}

}  // namespace anisomesh

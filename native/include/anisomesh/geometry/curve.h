#pragma once
// Parametric planar curves of the domain contours. Every curve is parameterized on
// t in [0, 1] and carries a Medit reference that becomes the reference of the boundary
// edges discretizing it.
#include <memory>
#include <string>
#include <vector>

#include "anisomesh/core/types.h"

namespace anisomesh {

class Curve {
 public:
  virtual ~Curve() = default;
  // Position at t in [0, 1].
  virtual Vec2 point(double t) const = 0;
  // First derivative dc/dt at t.
  virtual Vec2 derivative(double t) const = 0;
  // Second derivative d2c/dt2 at t.
  virtual Vec2 secondDerivative(double t) const = 0;
  // point(t) and derivative(t) at once, bit for bit (an arc shares its sine and cosine: the
  // metric-length integrands of contour discretization ask for both at every node).
  virtual void pointAndDerivative(double t, Vec2& p, Vec2& d) const {
    p = point(t);
    d = derivative(t);
  }
  // Euclidean length (closed form where one exists, adaptive Gauss-Legendre otherwise).
  virtual double length() const;
  // Interior parameters where the curve has a corner (polyline vertices, B-spline knots
  // of a degenerate control polygon are not reported); discretization keeps them as points.
  virtual std::vector<double> breakpoints() const { return {}; }
  // Short type name used in error messages ("line", "arc", ...).
  virtual const char* typeName() const = 0;

  Vec2 start() const { return point(0.0); }
  Vec2 end() const { return point(1.0); }
  int ref() const { return ref_; }
  void setRef(int ref) { ref_ = ref; }

 private:
  int ref_ = 0;
};

using CurvePtr = std::shared_ptr<const Curve>;

// Straight segment p1 -> p2.
class LineCurve : public Curve {
 public:
  LineCurve(const Vec2& p1, const Vec2& p2, int ref = 0);
  Vec2 point(double t) const override { return p1_ + t * (p2_ - p1_); }
  Vec2 derivative(double) const override { return p2_ - p1_; }
  Vec2 secondDerivative(double) const override { return Vec2::Zero(); }
  double length() const override { return (p2_ - p1_).norm(); }
  const char* typeName() const override { return "line"; }
  const Vec2& p1() const { return p1_; }
  const Vec2& p2() const { return p2_; }

 private:
  Vec2 p1_, p2_;
};

// Circular arc: center + radius (cos, sin)(a0 + t (a1 - a0)), angles in radians.
// a1 > a0 runs counter-clockwise; |a1 - a0| = 2 pi is a full circle.
class ArcCurve : public Curve {
 public:
  // Throws InvalidArgument on a non-positive or non-finite radius or non-finite angles.
  ArcCurve(const Vec2& center, double radius, double startAngle, double endAngle, int ref = 0);
  // The arc from a through b to c; throws InvalidArgument when the points are collinear or coincide.
  static ArcCurve throughPoints(const Vec2& a, const Vec2& b, const Vec2& c, int ref = 0);
  // Full counter-clockwise circle starting at angle 0.
  static ArcCurve circle(const Vec2& center, double radius, int ref = 0);
  Vec2 point(double t) const override;
  Vec2 derivative(double t) const override;
  void pointAndDerivative(double t, Vec2& p, Vec2& d) const override;
  Vec2 secondDerivative(double t) const override;
  double length() const override;
  const char* typeName() const override { return "arc"; }
  const Vec2& center() const { return center_; }
  double radius() const { return radius_; }
  double startAngle() const { return a0_; }
  double endAngle() const { return a1_; }

 private:
  Vec2 center_;
  double radius_, a0_, a1_;
};

// Open polyline through points, parameterized by arc length (vertices are breakpoints).
class PolylineCurve : public Curve {
 public:
  // Throws InvalidArgument with fewer than 2 points. With keepVertices false the inner
  // vertices are not breakpoints (discretization may move across them: remeshing).
  explicit PolylineCurve(std::vector<Vec2> points, int ref = 0, bool keepVertices = true);
  Vec2 point(double t) const override;
  Vec2 derivative(double t) const override;
  Vec2 secondDerivative(double) const override { return Vec2::Zero(); }
  double length() const override { return total_; }
  std::vector<double> breakpoints() const override;
  const char* typeName() const override { return "polyline"; }
  const std::vector<Vec2>& points() const { return pts_; }

 private:
  int segmentAt(double t, double* local) const;
  std::vector<Vec2> pts_;
  std::vector<double> cum_;  // cumulative parameter of each vertex, cum_[0] = 0, cum_.back() = 1
  double total_ = 0.0;
  bool keepVertices_ = true;
};

// C1 cubic spline interpolating points (a boundary reconstructed from its vertices: MMG's
// -hausd): cubic Hermite pieces, parameterized by chord length, with Bessel tangents (the
// derivative of the parabola through each vertex and its neighbours). before / after are
// the neighbours beyond the ends on a smooth boundary (the tangent there uses them, so
// consecutive pieces join C1); without them the end tangent is one-sided.
class SplineCurve : public Curve {
 public:
  // Throws InvalidArgument with fewer than 2 points or non-finite ones.
  SplineCurve(std::vector<Vec2> points, int ref = 0, const Vec2* before = nullptr, const Vec2* after = nullptr);
  Vec2 point(double t) const override;
  Vec2 derivative(double t) const override;
  Vec2 secondDerivative(double t) const override;
  const char* typeName() const override { return "spline"; }
  const std::vector<Vec2>& points() const { return pts_; }

 private:
  int segmentAt(double t, double* local) const;
  std::vector<Vec2> pts_, tangents_;  // tangents: dc/dt at the points
  std::vector<double> cum_;           // parameter of each point, cum_[0] = 0, cum_.back() = 1
};

// Cubic Bezier curve with 4 control points.
class BezierCurve : public Curve {
 public:
  BezierCurve(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, int ref = 0);
  Vec2 point(double t) const override;
  Vec2 derivative(double t) const override;
  Vec2 secondDerivative(double t) const override;
  const char* typeName() const override { return "bezier"; }

 private:
  Vec2 p_[4];
};

// Uniform clamped cubic B-spline (interpolates its first and last control points).
class BSplineCurve : public Curve {
 public:
  // Throws InvalidArgument with fewer than 4 control points.
  explicit BSplineCurve(std::vector<Vec2> controlPoints, int ref = 0);
  Vec2 point(double t) const override;
  Vec2 derivative(double t) const override;
  Vec2 secondDerivative(double t) const override;
  const char* typeName() const override { return "bspline"; }
  const std::vector<Vec2>& controlPoints() const { return ctrl_; }

 private:
  // Degree-p spline with knots k and control points c (de Boor), at t.
  static Vec2 evaluate(int degree, const std::vector<double>& knots, const std::vector<Vec2>& ctrl, double t);
  std::vector<Vec2> ctrl_, d1_, d2_;
  std::vector<double> knots_, knots1_, knots2_;
};

// Euclidean length of c between parameters a < b by adaptive Gauss-Legendre quadrature.
double curveLength(const Curve& c, double a = 0.0, double b = 1.0);

// Human-readable "(x, y)" for error messages.
std::string formatPoint(const Vec2& p);

}  // namespace anisomesh

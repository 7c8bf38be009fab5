#pragma once
// Fixed-size linear algebra types shared by every area of the core.
#include <Eigen/Core>
#include <Eigen/LU>

namespace anisomesh {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

// Axis-aligned rectangle [lo, hi] of the plane or of a patch's parameter domain.
struct Box2 {
  Vec2 lo{0.0, 0.0};
  Vec2 hi{0.0, 0.0};
  bool contains(const Vec2& p) const {
    return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
  }
  Vec2 size() const { return hi - lo; }
  Vec2 center() const { return 0.5 * (lo + hi); }
};

}  // namespace anisomesh

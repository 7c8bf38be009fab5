// Lines of principal directions of a control space (see principal_line.h).
#include "principal_line.h"

#include <algorithm>
#include <cmath>

#include "anisomesh/metric/sym_eigen.h"

namespace anisomesh {
namespace mesh_internal {
namespace {

// The unit principal direction at p closest to d (d unit), with d's sign, blended with d
// where the metric is nearly isotropic (its directions mean little there); false when the
// metric is not usable. hint: the caller's query hint (the steps follow each other).
bool principalStep(const ControlSpace& cs, const Vec2& p, const Vec2& d, double isotropicAspect, Vec2& out, int& hint) {
  const SymEigen2 e = symEigen(cs.metricAtNear(p, hint).transform());
  if (!(e.l2 > 0.0) || !std::isfinite(e.l1)) return false;
  const Vec2 u(pm::cos(e.theta), pm::sin(e.theta)), v(-u.y(), u.x());
  Vec2 w = std::fabs(u.dot(d)) >= std::fabs(v.dot(d)) ? u : v;
  if (w.dot(d) < 0.0) w = -w;
  const double weight = std::clamp((e.l1 / e.l2 - 1.0) / (isotropicAspect - 1.0), 0.0, 1.0);
  out = weight * w + (1.0 - weight) * d;
  const double n = out.norm();
  if (!(n > 0.0) || !std::isfinite(n)) return false;
  out /= n;
  return true;
}

// One way from seed along d: the points after seed up to the exit point; false when the
// line did not leave the region.
bool traceOneWay(const ControlSpace& cs, const Vec2& seed, Vec2 d, const RegionExit& exit,
                 const PrincipalLineOptions& o, std::vector<Vec2>& points, int& exitId) {
  Vec2 p = seed;
  int hint = -1;
  for (int k = 0; k < o.maxSteps; ++k) {
    Vec2 d1, d2;
    if (!principalStep(cs, p, d, o.isotropicAspect, d1, hint)) return false;
    if (!principalStep(cs, p + 0.5 * o.step * d1, d1, o.isotropicAspect, d2, hint)) return false;
    const Vec2 q = p + o.step * d2;
    double t = 0.0;
    if (exit(p, q, t, exitId)) {
      points.push_back(p + t * (q - p));
      return true;
    }
    points.push_back(q);
    p = q;
    d = d2;
  }
  return false;
}

}  // namespace

PrincipalLine tracePrincipalLine(const ControlSpace& cs, const Vec2& seed, const Vec2& along, const RegionExit& exit,
                                 const PrincipalLineOptions& options) {
  PrincipalLine line;
  Vec2 d0;
  int hint = -1;
  if (!(options.step > 0.0) || !principalStep(cs, seed, along.normalized(), options.isotropicAspect, d0, hint))
    return line;
  std::vector<Vec2> back, ahead;
  if (!traceOneWay(cs, seed, -d0, exit, options, back, line.firstExit) ||
      !traceOneWay(cs, seed, d0, exit, options, ahead, line.lastExit))
    return line;
  line.points.assign(back.rbegin(), back.rend());
  line.points.push_back(seed);
  line.points.insert(line.points.end(), ahead.begin(), ahead.end());
  return line;
}

}  // namespace mesh_internal
}  // namespace anisomesh

// Section 3.2 checks and control-space updates on planar boundary discretizations.
#include "anisomesh/boundary/boundary_updates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "anisomesh/boundary/discretize.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/core/int_conversion.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {
namespace {

double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

bool isCurved(const Curve& c) {
  const std::string t = c.typeName();
  return t != "line" && t != "polyline";
}

double curvatureRadius(const Curve& c, double t) {
  const Vec2 d1 = c.derivative(t), d2 = c.secondDerivative(t);
  const double cross = std::abs(d1.x() * d2.y() - d1.y() * d2.x());
  const double n = d1.norm();
  return cross > 0 ? n * n * n / cross : std::numeric_limits<double>::infinity();
}

// Where each boundary point sits: loop, index in the loop, arc length along the loop.
struct BoundaryIndex {
  std::vector<int> loop, index;
  std::vector<double> arc;
  std::vector<double> loopLength;
  std::vector<int> loopSize;
};

BoundaryIndex indexBoundary(const std::vector<BoundaryLoop>& loops) {
  BoundaryIndex b;
  for (size_t l = 0; l < loops.size(); ++l) {
    const auto& pts = loops[l].points;
    double s = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) {
      b.loop.push_back(int(l));
      b.index.push_back(int(i));
      b.arc.push_back(s);
      s += (pts[(i + 1) % pts.size()] - pts[i]).norm();
    }
    b.loopLength.push_back(s);
    b.loopSize.push_back(int(pts.size()));
  }
  return b;
}

// Two boundary points belong to non-adjacent boundary segments when they are on different
// loops, or farther apart along the loop than twice their distance (a gap or a narrow
// part, not a gently curved contour) and not neighbours.
bool nonAdjacent(const BoundaryIndex& b, const std::vector<Vec2>& pts, int i, int j) {
  if (b.loop[i] != b.loop[j]) return true;
  const int n = b.loopSize[b.loop[i]];
  const int di = std::abs(b.index[i] - b.index[j]);
  if (std::min(di, n - di) < 2) return false;
  const double da = std::abs(b.arc[i] - b.arc[j]);
  const double along = std::min(da, b.loopLength[b.loop[i]] - da);
  return along > 2.0 * (pts[i] - pts[j]).norm();
}

}  // namespace

double segmentMetricLength(const ControlSpace& cs, const Vec2& p, const Vec2& q) {
  const Vec2 d = q - p;
  return (cs.metricAt(p).length(d) + 4.0 * cs.metricAt(0.5 * (p + q)).length(d) + cs.metricAt(q).length(d)) / 6.0;
}

SegmentLengthCheck checkSegmentLengths(const std::vector<BoundaryLoop>& loops, const ControlSpace& cs,
                                       const BoundaryUpdateOptions& o) {
  SegmentLengthCheck r;
  r.invalidContours.assign(loops.size(), 0);
  for (size_t l = 0; l < loops.size(); ++l) {
    const auto& pts = loops[l].points;
    for (size_t i = 0; i < pts.size(); ++i) {
      const Vec2 &p = pts[i], &q = pts[(i + 1) % pts.size()];
      const double len = segmentMetricLength(cs, p, q);
      if (len < o.eps1) r.shortSegments.push_back({p, q, len, int(l)});
      if (len < o.lengthMin || len > o.lengthMax) {
        ++r.invalidSegments;
        r.invalidContours[l] = 1;
      }
    }
  }
  return r;
}

int shortSegmentSources(const std::vector<ShortSegment>& segments, const ControlSpace& cs, double hmin,
                        std::vector<MetricSource>* out) {
  int added = 0;
  for (const ShortSegment& s : segments) {
    const double reference = (s.q - s.p).norm();
    if (!(s.length > 0.0) || !(reference > 0.0)) continue;
    // Sizes times the metric length: the segment is one unit long in the new metric.
    const Metric m = cs.metricAt(0.5 * (s.p + s.q)).scaled(s.length);
    if (hmin > 0.0) {
      const Metric clamped = clampMetricSizes(m, hmin, std::numeric_limits<double>::infinity());
      if (!(s.length / clamped.length(s.q - s.p) < 0.95)) continue;  // the clamp undoes it
    }
    out->emplace_back(std::in_place_type<SegmentSource>, SegmentSource{s.p, s.q, m, reference});
    ++added;
  }
  return added;
}

// Largest distance of c([a, b]) from its chord, by sampling.
double chordDeviation(const Curve& c, double a, double b) {
  const Vec2 p = c.point(a), q = c.point(b);
  double dev = 0.0;
  constexpr int kSamples = 8;
  for (int k = 1; k < kSamples; ++k)
    dev = std::max(dev, pointSegmentDistance(c.point(a + (b - a) * k / kSamples), p, q));
  return dev;
}

// Section 3.2 (b): curvature sources along the chords of curved contours deviating
// from the curve by more than tolerance * chord. Returns the largest relative deviation.
double chordSources(const Domain& domain, const ControlSpace& cs, const BoundaryUpdateOptions& o,
                    std::vector<MetricSource>* out, std::vector<char>* invalidContours) {
  double worst = 0.0;
  std::vector<const Contour*> contours{&domain.outer};
  for (const Contour& h : domain.holes) contours.push_back(&h);
  for (size_t ci = 0; ci < contours.size(); ++ci) {
    const Contour* contour = contours[ci];
    for (const CurveUse& use : contour->curves) {
      const Curve& c = *use.curve;
      if (!isCurved(c)) continue;
      const std::vector<double> ts = discretizeCurve(c, cs, contour->curves.size() == 1 ? 3 : 1);
      for (size_t i = 0; i + 1 < ts.size(); ++i) {
        const double chord = (c.point(ts[i + 1]) - c.point(ts[i])).norm();
        if (chord <= 0) continue;
        const double dev = chordDeviation(c, ts[i], ts[i + 1]), rel = dev / chord;
        worst = std::max(worst, rel);
        if (rel <= o.chordTolerance && !(o.chordDistance > 0 && dev > o.chordDistance)) continue;
        if (invalidContours && ci < invalidContours->size()) (*invalidContours)[ci] = 1;
        // Tangent size from the sagitta s = h^2 / (8 R): s / h <= tol for h <= 8 R tol;
        // 0.75 leaves room for the rounding of the discretization.
        const int pieces = 8;
        for (int k = 0; k < pieces; ++k) {
          const double a = ts[i] + (ts[i + 1] - ts[i]) * k / pieces, b = ts[i] + (ts[i + 1] - ts[i]) * (k + 1) / pieces;
          const double r = std::min({curvatureRadius(c, a), curvatureRadius(c, 0.5 * (a + b)), curvatureRadius(c, b)});
          if (!std::isfinite(r)) continue;
          double h1 = 0.75 * 8.0 * r * o.chordTolerance;
          if (o.chordDistance > 0) h1 = std::min(h1, 0.75 * std::sqrt(8.0 * r * o.chordDistance));
          const Vec2 t = c.derivative(0.5 * (a + b));
          const Vec2 pa = c.point(a), pb = c.point(b);
          if ((pb - pa).norm() <= 1e-12 * std::max(1.0, pa.norm())) continue;
          out->emplace_back(std::in_place_type<SegmentSource>,
                            SegmentSource{pa, pb, Metric::fromSizes(pm::atan2(t.y(), t.x()), h1, o.dMax * h1),
                                          chordDeviation(c, a, b)});  // emplace: see case_control_space.cpp
        }
      }
    }
  }
  return worst;
}

int proximitySources(const std::vector<BoundaryLoop>& loops, const Mesh& boundaryMesh, const ControlSpace& cs,
                     const BoundaryUpdateOptions& o, std::vector<MetricSource>* out) {
  const BoundaryIndex b = indexBoundary(loops);
  std::vector<Vec2> pts;
  for (const Vec3& p : boundaryMesh.points) pts.push_back(p.head<2>());
  const int nb = int(b.loop.size());
  std::vector<Mat2> mt(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) mt[i] = cs.metricAt(pts[i]).transform();
  const double unitArea = std::sqrt(3.0) / 4.0;
  int added = 0;
  for (const auto& t : boundaryMesh.triangles) {
    if (t[0] >= nb || t[1] >= nb || t[2] >= nb) continue;
    if (!nonAdjacent(b, pts, t[0], t[1]) && !nonAdjacent(b, pts, t[1], t[2]) && !nonAdjacent(b, pts, t[2], t[0]))
      continue;
    const Vec2 &p0 = pts[t[0]], &p1 = pts[t[1]], &p2 = pts[t[2]];
    const Vec2 e1 = p1 - p0, e2 = p2 - p0;
    const double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    const Mat2 m = (mt[t[0]] + mt[t[1]] + mt[t[2]]) / 3.0;
    if (area * std::abs(m.determinant()) >= o.eps2 * unitArea) continue;
    const double longest = std::max({e1.norm(), e2.norm(), (p2 - p1).norm()});
    const double width = 2.0 * area / longest;  // the triangle's height across its longest edge
    if (!(width > 0)) continue;
    const Vec2 centroid = (p0 + p1 + p2) / 3.0;
    const double radius = std::max({(p0 - centroid).norm(), (p1 - centroid).norm(), (p2 - centroid).norm()});
    out->emplace_back(std::in_place_type<RadialSource>,
                      RadialSource{centroid, Metric::isotropic(width / o.gapElements), radius});
    ++added;
  }
  return added;
}

int refineNearSegments(AdaptiveControlSpace& cs, const std::vector<ShortSegment>& segments,
                       const MetricFunction& analytic) {
  if (segments.empty()) return 0;
  // A uniform grid of segment boxes keeps the predicate cheap.
  const Box2 box = cs.bounds();
  const int side = std::clamp(int(std::sqrt(double(segments.size()))) + 1, 1, 256);
  const Vec2 cell = box.size() / double(side);
  std::vector<std::vector<int>> grid(size_t(side) * side);
  auto cellOf = [&](double v, double lo, double h) { return clampedCell((v - lo) / h, side); };
  for (size_t k = 0; k < segments.size(); ++k) {
    const Vec2 lo = segments[k].p.cwiseMin(segments[k].q), hi = segments[k].p.cwiseMax(segments[k].q);
    for (int y = cellOf(lo.y(), box.lo.y(), cell.y()); y <= cellOf(hi.y(), box.lo.y(), cell.y()); ++y)
      for (int x = cellOf(lo.x(), box.lo.x(), cell.x()); x <= cellOf(hi.x(), box.lo.x(), cell.x()); ++x)
        grid[size_t(y) * side + x].push_back(int(k));
  }
  const int before = cs.elementCount();
  cs.refine(
      [&](const ControlElement& e) {
        for (int y = cellOf(e.box.lo.y(), box.lo.y(), cell.y()); y <= cellOf(e.box.hi.y(), box.lo.y(), cell.y()); ++y)
          for (int x = cellOf(e.box.lo.x(), box.lo.x(), cell.x()); x <= cellOf(e.box.hi.x(), box.lo.x(), cell.x()); ++x)
            for (int k : grid[size_t(y) * side + x]) {
              const Vec2 &a = segments[k].p, &b = segments[k].q;
              if (e.size <= (b - a).norm()) continue;
              if (segmentBoxDistance(a, b, e.box) <= 0.0) return true;
            }
        return false;
      },
      [&](int first, int last) {
        if (!analytic) return;
        for (int i = first; i < last; ++i)
          if (cs.nodeIsFree(i)) cs.setNodeMetric(i, intersect(cs.nodeMetric(i), analytic(cs.nodePosition(i))));
      });
  cs.applyConstraints();
  return cs.elementCount() - before;
}

std::vector<char> keepValidContours(std::vector<BoundaryLoop>& loops, const std::vector<BoundaryLoop>& fresh,
                                    const std::vector<char>& invalidContours) {
  std::vector<char> isFresh(fresh.size(), 1);
  if (loops.size() != fresh.size()) {
    loops = fresh;
    return isFresh;
  }
  for (size_t k = 0; k < fresh.size(); ++k) {
    isFresh[k] = k < invalidContours.size() && invalidContours[k];
    if (isFresh[k]) loops[k] = fresh[k];
  }
  // Fresh loops are free of crossings among themselves (discretizeDomains); a kept loop
  // that crosses one is re-discretized too.
  for (size_t round = 0; round <= loops.size(); ++round) {
    std::vector<std::vector<Vec2>> polygons;
    polygons.reserve(loops.size());
    for (const BoundaryLoop& l : loops) polygons.push_back(l.points);
    PolygonCrossing x;
    if (!findPolygonCrossing(polygons, &x)) break;
    bool replaced = false;
    for (int k : {x.polygonA, x.polygonB})
      if (!isFresh[size_t(k)]) {
        isFresh[size_t(k)] = 1;
        loops[size_t(k)] = fresh[size_t(k)];
        replaced = true;
      }
    if (!replaced) break;  // cannot happen: fresh loops do not cross
  }
  return isFresh;
}

}  // namespace anisomesh

#include "anisomesh/geometry/domain.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

// Parameters splitting a curve into its smooth pieces: 0, breakpoints..., 1.
std::vector<double> smoothPieceBounds(const Curve& c) {
  std::vector<double> b{0.0};
  for (double t : c.breakpoints())
    if (t > b.back() && t < 1.0) b.push_back(t);
  b.push_back(1.0);
  return b;
}

bool isStraight(const Curve& c) {
  const std::string type = c.typeName();
  return type == "line" || type == "polyline";
}

// Samples of one curve use, from its start up to but excluding its end.
void sampleUse(const CurveUse& use, int samples, std::vector<Vec2>* out) {
  const Curve& c = *use.curve;
  if (const auto* poly = dynamic_cast<const PolylineCurve*>(&c)) {
    // Exactly its vertices, whether or not they are breakpoints.
    std::vector<Vec2> pts = poly->points();
    if (use.reversed) std::reverse(pts.begin(), pts.end());
    out->insert(out->end(), pts.begin(), pts.end() - 1);
    return;
  }
  const std::vector<double> b = smoothPieceBounds(c);
  std::vector<double> ts;
  const int per = isStraight(c) ? 1 : std::max(1, samples);
  for (size_t k = 0; k + 1 < b.size(); ++k)
    for (int i = 0; i < per; ++i) ts.push_back(b[k] + (b[k + 1] - b[k]) * i / per);
  if (use.reversed) {
    // Backwards: the same parameters from t = 1 down to (but excluding) t = 0.
    ts.push_back(1.0);
    ts.erase(ts.begin());
    std::reverse(ts.begin(), ts.end());
  }
  for (double t : ts) out->push_back(c.point(t));
}

struct Segment {
  Vec2 a, b;
  int polygon;  // index of its polygon
  int index;    // index of the segment in its polygon
  int count;    // number of segments of its polygon
};

std::string curveName(const Domain& d, int contour, int curve) {
  const Contour& c = contour == 0 ? d.outer : d.holes[contour - 1];
  std::ostringstream os;
  os << contourName(contour) << ", curve " << curve << " (" << c.curves[curve].curve->typeName() << ")";
  return os.str();
}

double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

// Where segments s and t meet (crossing, touching, overlapping), if they do. tol is a
// distance: a point within tol of a segment's line counts as on it (a tolerance on the cross
// products themselves would grow as 1 / length for short segments: refining two curves
// 1e-6 apart made their segments "touch", which refined them further, without end).
bool segmentsMeet(const Segment& s, const Segment& t, double tol, Vec2* where) {
  const double ls = (s.b - s.a).norm(), lt = (t.b - t.a).norm();
  const double es = tol * ls, et = tol * lt;  // cross product tolerances: distance times length
  const double o1 = cross(s.b - s.a, t.a - s.a), o2 = cross(s.b - s.a, t.b - s.a);
  const double o3 = cross(t.b - t.a, s.a - t.a), o4 = cross(t.b - t.a, s.b - t.a);
  if (((o1 > es && o2 < -es) || (o1 < -es && o2 > es)) && ((o3 > et && o4 < -et) || (o3 < -et && o4 > et))) {
    const double u = o3 / (o3 - o4);
    *where = s.a + u * (s.b - s.a);
    return true;
  }
  // Touching: an end point of one lies on the other.
  auto onSegment = [](const Vec2& p, const Vec2& a, const Vec2& b, double o, double e) {
    if (std::abs(o) > e) return false;
    const Vec2 ab = b - a;
    const double l2 = ab.squaredNorm();
    if (l2 == 0) return (p - a).squaredNorm() == 0;
    const double u = (p - a).dot(ab) / l2;
    return u >= -1e-12 && u <= 1 + 1e-12;
  };
  if (onSegment(t.a, s.a, s.b, o1, es)) return *where = t.a, true;
  if (onSegment(t.b, s.a, s.b, o2, es)) return *where = t.b, true;
  if (onSegment(s.a, t.a, t.b, o3, et)) return *where = s.a, true;
  if (onSegment(s.b, t.a, t.b, o4, et)) return *where = s.b, true;
  return false;
}

// Adjacent segments of one contour share their common end point; they only "meet"
// when they fold back onto each other (the second within tol of the first's line).
bool adjacentFold(const Segment& s, const Segment& t, double tol) {
  const Segment& first = (t.index == (s.index + 1) % s.count) ? s : t;
  const Segment& second = (&first == &s) ? t : s;
  const Vec2 u = first.b - first.a, v = second.b - second.a;
  return std::abs(cross(u, v)) <= tol * u.norm() && u.dot(v) < 0;
}

}  // namespace

std::string contourName(int contourIndex) {
  return contourIndex == 0 ? std::string("outer") : "holes[" + std::to_string(contourIndex - 1) + "]";
}

std::vector<Vec2> sampleContour(const Contour& contour, int samplesPerCurve) {
  std::vector<Vec2> pts;
  for (const CurveUse& use : contour.curves) sampleUse(use, samplesPerCurve, &pts);
  return pts;
}

Box2 domainBounds(const Domain& domain) {
  Box2 box{Vec2::Constant(INFINITY), Vec2::Constant(-INFINITY)};
  auto add = [&box](const Contour& c) {
    for (const Vec2& p : sampleContour(c, 16)) {
      box.lo = box.lo.cwiseMin(p);
      box.hi = box.hi.cwiseMax(p);
    }
  };
  add(domain.outer);
  for (const Contour& h : domain.holes) add(h);
  if (!(box.lo.x() <= box.hi.x())) box = Box2{};
  return box;
}

double signedArea(const std::vector<Vec2>& polygon) {
  double a = 0.0;
  for (size_t i = 0, n = polygon.size(); i < n; ++i) a += cross(polygon[i], polygon[(i + 1) % n]);
  return 0.5 * a;
}

bool pointInPolygon(const std::vector<Vec2>& polygon, const Vec2& p) {
  bool inside = false;
  for (size_t i = 0, n = polygon.size(), j = n - 1; i < n; j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

bool findPolygonCrossing(const std::vector<std::vector<Vec2>>& polygons, PolygonCrossing* out) {
  std::vector<Segment> segs;
  Box2 box{Vec2::Constant(INFINITY), Vec2::Constant(-INFINITY)};
  for (size_t k = 0; k < polygons.size(); ++k) {
    const auto& pts = polygons[k];
    const int n = int(pts.size());
    for (int i = 0; i < n; ++i) {
      segs.push_back({pts[size_t(i)], pts[size_t((i + 1) % n)], int(k), i, n});
      box.lo = box.lo.cwiseMin(pts[size_t(i)]);
      box.hi = box.hi.cwiseMax(pts[size_t(i)]);
    }
  }
  if (segs.empty()) return false;
  const double diag = box.size().norm() > 0 ? box.size().norm() : 1.0;
  // Uniform grid over the bounding box; every segment is binned in the cells its box covers.
  const double tol = 1e-12 * diag;  // distance within which points meet
  const int side = std::max(1, std::min(1024, int(std::sqrt(double(segs.size())))));
  const Vec2 lo = box.lo, extent = box.size().cwiseMax(Vec2::Constant(1e-300));
  auto cellOf = [&](double v, int axis) {
    const int c = int((v - lo[axis]) / extent[axis] * side);
    return std::min(std::max(c, 0), side - 1);
  };
  std::vector<std::vector<int>> cells(size_t(side) * side);
  for (int s = 0; s < int(segs.size()); ++s) {
    const Vec2 a = segs[size_t(s)].a.cwiseMin(segs[size_t(s)].b), b = segs[size_t(s)].a.cwiseMax(segs[size_t(s)].b);
    for (int x = cellOf(a.x(), 0); x <= cellOf(b.x(), 0); ++x)
      for (int y = cellOf(a.y(), 1); y <= cellOf(b.y(), 1); ++y) cells[size_t(y) * side + x].push_back(s);
  }
  // Boxes grown by the distance within which segmentsMeet calls an end point "on" a
  // segment (tol, plus its 1e-12 parameter slack): pairs whose grown boxes are apart
  // cannot meet, so they are skipped without changing which pair is found.
  std::vector<Box2> grown(segs.size());
  for (size_t s = 0; s < segs.size(); ++s) {
    const double len = (segs[s].b - segs[s].a).norm();
    const double margin = len > 0 ? tol + 1e-12 * len : 0.0;
    grown[s] = {segs[s].a.cwiseMin(segs[s].b) - Vec2::Constant(margin),
                segs[s].a.cwiseMax(segs[s].b) + Vec2::Constant(margin)};
  }
  auto overlap = [&](int s, int t) {
    return (grown[size_t(s)].lo.array() <= grown[size_t(t)].hi.array()).all() &&
           (grown[size_t(t)].lo.array() <= grown[size_t(s)].hi.array()).all();
  };
  std::vector<int> order;
  std::vector<std::pair<int, int>> candidates;
  for (const auto& cell : cells) {
    // Candidate pairs (positions i < j in the cell) by a sweep along the axis the cell's
    // segments spread over most, then tested in the order of the plain double loop over
    // (i, j): the first meeting pair is the one that loop would find.
    const int n = int(cell.size());
    if (n < 2) continue;
    Vec2 clo = Vec2::Constant(INFINITY), chi = Vec2::Constant(-INFINITY);
    for (int s : cell) clo = clo.cwiseMin(grown[size_t(s)].lo), chi = chi.cwiseMax(grown[size_t(s)].hi);
    const int axis = chi.x() - clo.x() >= chi.y() - clo.y() ? 0 : 1;
    order.resize(size_t(n));
    for (int i = 0; i < n; ++i) order[size_t(i)] = i;
    std::sort(order.begin(), order.end(), [&](int i, int j) {
      const double a = grown[size_t(cell[size_t(i)])].lo[axis], b = grown[size_t(cell[size_t(j)])].lo[axis];
      return a < b || (a == b && i < j);
    });
    candidates.clear();
    for (int k = 0; k < n; ++k) {
      const int i = order[size_t(k)];
      const double hi = grown[size_t(cell[size_t(i)])].hi[axis];
      for (int m = k + 1; m < n; ++m) {
        const int j = order[size_t(m)];
        if (grown[size_t(cell[size_t(j)])].lo[axis] > hi) break;
        if (overlap(cell[size_t(i)], cell[size_t(j)])) candidates.emplace_back(std::min(i, j), std::max(i, j));
      }
    }
    std::sort(candidates.begin(), candidates.end());
    for (const auto& pair : candidates) {
      const Segment& s = segs[size_t(cell[size_t(pair.first)])];
      const Segment& t = segs[size_t(cell[size_t(pair.second)])];
      Vec2 where;
      bool meet;
      if (s.polygon == t.polygon && s.count > 1 &&
          (t.index == (s.index + 1) % s.count || s.index == (t.index + 1) % s.count)) {
        if (s.count == 2) continue;
        meet = adjacentFold(s, t, tol);
        where = (t.index == (s.index + 1) % s.count) ? s.b : s.a;
      } else {
        meet = segmentsMeet(s, t, tol, &where);
      }
      if (meet) {
        *out = {s.polygon, s.index, t.polygon, t.index, where};
        return true;
      }
    }
  }
  return false;
}

void validateDomain(const Domain& domain, const DomainValidationOptions& options) {
  std::vector<const Contour*> contours{&domain.outer};
  for (const Contour& h : domain.holes) contours.push_back(&h);

  for (size_t k = 0; k < contours.size(); ++k)
    require(!contours[k]->curves.empty(), ErrorCode::OpenContour, contourName(int(k)) + ": contour has no curves");
  const Box2 box = domainBounds(domain);
  const double diag = box.size().norm() > 0 ? box.size().norm() : 1.0;

  // Zero-length curves first: they would also make the closure test meaningless.
  for (size_t k = 0; k < contours.size(); ++k)
    for (size_t i = 0; i < contours[k]->curves.size(); ++i) {
      const CurveUse& u = contours[k]->curves[i];
      require(u.curve != nullptr, ErrorCode::InvalidArgument,
              contourName(int(k)) + ", curve " + std::to_string(i) + ": null curve");
      require(u.curve->length() > options.zeroLengthTolerance * diag, ErrorCode::ZeroLengthCurve,
              curveName(domain, int(k), int(i)) + ": zero length at " + formatPoint(u.curve->start()));
    }

  // Closed chains.
  for (size_t k = 0; k < contours.size(); ++k) {
    const auto& cs = contours[k]->curves;
    for (size_t i = 0; i < cs.size(); ++i) {
      const size_t j = (i + 1) % cs.size();
      const Vec2 e = cs[i].end(), s = cs[j].start();
      const double gap = (e - s).norm();
      if (gap > options.closeTolerance * diag) {
        std::ostringstream os;
        os << curveName(domain, int(k), int(i)) << " ends at " << formatPoint(e) << " but "
           << (j == 0 ? "the first curve, " : "the next curve, ") << "curve " << j << ", starts at " << formatPoint(s)
           << " (gap " << gap << "): the contour is not closed";
        throw Error(ErrorCode::OpenContour, os.str());
      }
    }
  }

  // Polyline approximation with the curve index of each segment.
  std::vector<std::vector<Vec2>> polygons;
  std::vector<std::vector<int>> owners;
  for (size_t k = 0; k < contours.size(); ++k) {
    std::vector<Vec2> pts;
    std::vector<int> owner;
    for (size_t i = 0; i < contours[k]->curves.size(); ++i) {
      const size_t before = pts.size();
      sampleUse(contours[k]->curves[i], options.samplesPerCurve, &pts);
      owner.insert(owner.end(), pts.size() - before, int(i));
    }
    polygons.push_back(std::move(pts));
    owners.push_back(std::move(owner));
  }
  PolygonCrossing x;
  if (findPolygonCrossing(polygons, &x)) {
    const std::string what = x.polygonA == x.polygonB ? "the contour intersects itself" : "the contours cross or touch";
    throw Error(ErrorCode::SelfIntersectingContour,
                curveName(domain, x.polygonA, owners[size_t(x.polygonA)][size_t(x.segmentA)]) + " meets " +
                    curveName(domain, x.polygonB, owners[size_t(x.polygonB)][size_t(x.segmentB)]) + " near " +
                    formatPoint(x.where) + ": " + what);
  }

  // With no crossings, one point decides containment (bounding boxes skip far holes).
  std::vector<Box2> boxes;
  for (const auto& poly : polygons) {
    Box2 b{poly[0], poly[0]};
    for (const Vec2& p : poly) b.lo = b.lo.cwiseMin(p), b.hi = b.hi.cwiseMax(p);
    boxes.push_back(b);
  }
  for (size_t k = 1; k < contours.size(); ++k) {
    const Vec2 p = polygons[k][0];
    require(pointInPolygon(polygons[0], p), ErrorCode::HoleOutsideDomain,
            contourName(int(k)) + " is not inside the outer contour: its point " + formatPoint(p) + " lies outside");
    for (size_t j = 1; j < contours.size(); ++j) {
      if (j == k || !boxes[j].contains(p)) continue;
      require(!pointInPolygon(polygons[j], p), ErrorCode::HoleOutsideDomain,
              contourName(int(k)) + " lies inside " + contourName(int(j)) + " (holes must not overlap): its point " +
                  formatPoint(p) + " is inside " + contourName(int(j)));
    }
  }
}

}  // namespace anisomesh

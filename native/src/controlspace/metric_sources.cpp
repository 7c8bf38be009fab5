#include "anisomesh/controlspace/metric_sources.h"
#include "anisomesh/core/number_text.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {
namespace {

// The messages are built only on failure (these run once per source).
void checkPoint(const Vec2& p, const char* what) {
  if (!p.allFinite()) throw Error(ErrorCode::InvalidArgument, std::string(what) + " has a NaN or infinite coordinate");
}

void checkRadius(double r, const char* what) {
  if (!(std::isfinite(r) && r >= 0.0))
    throw Error(ErrorCode::InvalidArgument,
                std::string(what) + " radius must be finite and >= 0, got " + numberText(r));
}

bool isZeroLength(const Vec2& a, const Vec2& b) {
  const double scale = std::max({1.0, a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff()});
  return (b - a).norm() <= 1e-14 * scale;
}

// Distance from a point to the box (0 inside).
double pointBoxDistance(const Vec2& p, const Box2& box) {
  const double dx = std::max({box.lo.x() - p.x(), 0.0, p.x() - box.hi.x()});
  const double dy = std::max({box.lo.y() - p.y(), 0.0, p.y() - box.hi.y()});
  return pm::hypot(dx, dy);
}

// Liang-Barsky: does segment ab meet the box?
bool segmentMeetsBox(const Vec2& a, const Vec2& b, const Box2& box) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x() - box.lo.x(), box.hi.x() - a.x(), a.y() - box.lo.y(), box.hi.y() - a.y()};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
    } else {
      const double t = q[i] / p[i];
      if (p[i] < 0.0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
      if (t0 > t1) return false;
    }
  }
  return true;
}

double segmentPointDistance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

}  // namespace

double segmentBoxDistance(const Vec2& a, const Vec2& b, const Box2& box) {
  if (a == b) return pointBoxDistance(a, box);  // a point: no clipping or corners needed
  if (segmentMeetsBox(a, b, box)) return 0.0;
  double d = std::min(pointBoxDistance(a, box), pointBoxDistance(b, box));
  const Vec2 corners[4] = {box.lo, {box.hi.x(), box.lo.y()}, box.hi, {box.lo.x(), box.hi.y()}};
  for (const Vec2& c : corners) d = std::min(d, segmentPointDistance(a, b, c));
  return d;
}

double distanceToPiece(const SourcePiece& piece, const Vec2& p) { return segmentPointDistance(piece.a, piece.b, p); }

std::vector<SourcePiece> sourcePieces(const std::vector<MetricSource>& sources, const Box2& box,
                                      const SourceOptions& options) {
  require(std::isfinite(options.sizeFactor) && options.sizeFactor > 0.0, ErrorCode::InvalidArgument,
          "source sizeFactor must be finite and positive");
  std::vector<SourcePiece> pieces;
  auto add = [&](const Vec2& a, const Vec2& b, const Metric& m, double r) {
    SourcePiece p;
    p.a = a;
    p.b = b;
    p.metric = m;
    p.radius = r;
    p.targetSize = std::max(r, m.smallestSize()) * options.sizeFactor;
    if (segmentBoxDistance(a, b, box) <= r) pieces.push_back(p);  // outside: no-op
  };
  for (const MetricSource& src : sources) {
    if (const auto* s = std::get_if<RadialSource>(&src)) {
      checkPoint(s->center, "radial source center");
      checkRadius(s->radius, "radial source");
      add(s->center, s->center, s->metric, s->radius);
    } else if (const auto* s = std::get_if<SegmentSource>(&src)) {
      checkPoint(s->a, "segment source end");
      checkPoint(s->b, "segment source end");
      checkRadius(s->radius, "segment source");
      require(!isZeroLength(s->a, s->b), ErrorCode::ZeroLengthCurve, "segment source has zero length");
      add(s->a, s->b, s->metric, s->radius);
    } else if (const auto* s = std::get_if<CurveSource>(&src)) {
      checkRadius(s->radius, "curve source");
      require(static_cast<bool>(s->curve), ErrorCode::InvalidArgument, "curve source has no curve function");
      require(std::isfinite(s->t1) && std::isfinite(s->t2), ErrorCode::InvalidArgument,
              "curve source parameter range must be finite");
      require(s->t1 != s->t2, ErrorCode::ZeroLengthCurve, "curve source has an empty parameter range");
      // Adaptive sampling: split a parameter interval while the curve's midpoint is farther
      // than a quarter of the source size from the chord.
      const double tol = 0.25 * std::max(s->radius, s->metric.smallestSize());
      std::vector<Vec2> pts;
      auto eval = [&](double t) {
        Vec2 p = s->curve(t);
        checkPoint(p, "curve source point");
        return p;
      };
      struct Item {
        double t0, t1;
        Vec2 p0, p1;
        int depth;
      };
      const int n0 = 16;
      std::vector<Item> stack;
      Vec2 prev = eval(s->t1);
      pts.push_back(prev);
      for (int i = 1; i <= n0; ++i) {
        const double t0 = s->t1 + (s->t2 - s->t1) * (i - 1) / n0, t1 = s->t1 + (s->t2 - s->t1) * i / n0;
        const Vec2 p1 = eval(t1);
        stack.push_back({t0, t1, prev, p1, 0});
        while (!stack.empty()) {
          Item it = stack.back();
          stack.pop_back();
          const double tm = 0.5 * (it.t0 + it.t1);
          const Vec2 pm = eval(tm);
          if (it.depth < 12 && segmentPointDistance(it.p0, it.p1, pm) > tol) {
            stack.push_back({tm, it.t1, pm, it.p1, it.depth + 1});  // second half after
            stack.push_back({it.t0, tm, it.p0, pm, it.depth + 1});
          } else {
            pts.push_back(it.p1);
          }
        }
        prev = p1;
      }
      double length = 0.0;
      for (size_t i = 1; i < pts.size(); ++i) length += (pts[i] - pts[i - 1]).norm();
      require(length > 0.0 && !isZeroLength(pts.front(), pts.front() + Vec2(length, 0.0)), ErrorCode::ZeroLengthCurve,
              "curve source has zero length");
      for (size_t i = 1; i < pts.size(); ++i)
        if (!isZeroLength(pts[i - 1], pts[i])) add(pts[i - 1], pts[i], s->metric, s->radius);
    } else if (const auto* s = std::get_if<PolylineSource>(&src)) {
      checkRadius(s->radius, "polyline source");
      require(s->points.size() >= 2, ErrorCode::InvalidArgument, "polyline source needs at least 2 points");
      double length = 0.0;
      for (const Vec2& p : s->points) checkPoint(p, "polyline source point");
      for (size_t i = 1; i < s->points.size(); ++i) length += (s->points[i] - s->points[i - 1]).norm();
      require(length > 0.0, ErrorCode::ZeroLengthCurve, "polyline source has zero length");
      for (size_t i = 1; i < s->points.size(); ++i)
        if (!isZeroLength(s->points[i - 1], s->points[i])) add(s->points[i - 1], s->points[i], s->metric, s->radius);
    } else if (const auto* s = std::get_if<NodeSource>(&src)) {
      require(s->points.size() == s->metrics.size(), ErrorCode::InvalidArgument,
              "node source needs one metric per point");
      for (size_t i = 0; i < s->points.size(); ++i) {
        checkPoint(s->points[i], "node source point");
        add(s->points[i], s->points[i], s->metrics[i], 0.0);
      }
    }
  }
  return pieces;
}

}  // namespace anisomesh

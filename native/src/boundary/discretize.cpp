#include "anisomesh/boundary/discretize.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/quadrature.h"

namespace anisomesh {
namespace {

using Integrand = std::function<double(double)>;

struct Leaf {
  double a, b, value;
};

// Adaptive bisection that keeps its leaves, so the cumulative metric length can be
// inverted locally; leaves are also capped in width so the inversion stays accurate.
void collectLeaves(const Integrand& f, double a, double b, double whole, double tol, double absTol, double maxWidth,
                   int depth, std::vector<Leaf>* out) {
  const double m = 0.5 * (a + b);
  const double left = gaussLegendre5(f, a, m), right = gaussLegendre5(f, m, b);
  const bool converged = std::abs(left + right - whole) <= std::max(tol * (1.0 + std::abs(left + right)), absTol);
  if (depth <= 0 || (converged && b - a <= maxWidth)) {
    out->push_back({a, m, left});
    out->push_back({m, b, right});
    return;
  }
  collectLeaves(f, a, m, left, tol, absTol, maxWidth, depth - 1, out);
  collectLeaves(f, m, b, right, tol, absTol, maxWidth, depth - 1, out);
}

// Solves start + integral_{leaf.a}^{t} f = target for t inside the leaf (Newton, bracketed).
double invertInLeaf(const Integrand& f, const Leaf& leaf, double start, double target) {
  double lo = leaf.a, hi = leaf.b;
  double t = leaf.value > 0 ? leaf.a + (leaf.b - leaf.a) * (target - start) / leaf.value : 0.5 * (lo + hi);
  t = std::min(std::max(t, lo), hi);
  for (int it = 0; it < 40; ++it) {
    const double g = start + gaussLegendre5(f, leaf.a, t) - target;
    if (std::abs(g) <= 1e-12 * (1.0 + std::abs(target))) break;
    if (g > 0)
      hi = t;
    else
      lo = t;
    const double d = f(t);
    double next = d > 0 ? t - g / d : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= 1e-15 * (1.0 + std::abs(t))) break;
    t = next;
  }
  return t;
}

struct Piece {
  double a, b;
  std::vector<Leaf> leaves;
  double length = 0.0;
  int segments = 1;
};

// |c'(t)| in the metric at c(t): the integrand of the metric length. hint: the caller's
// query hint (the quadrature's points follow each other along the curve).
double metricSpeed(const Curve& c, const ControlSpace& cs, double t, int& hint) {
  Vec2 p, d;
  c.pointAndDerivative(t, p, d);
  return cs.metricAtNear(p, hint).length(d);
}

// Parameter bounds of the smooth pieces of c: 0, its increasing breakpoints inside (0, 1), 1.
std::vector<double> pieceBounds(const Curve& c) {
  std::vector<double> bounds{0.0};
  for (double t : c.breakpoints())
    if (t > bounds.back() && t < 1.0) bounds.push_back(t);
  bounds.push_back(1.0);
  return bounds;
}

}  // namespace

double metricLength(const Curve& c, const ControlSpace& cs, double a, double b, double tolerance) {
  int hint = -1;
  return integrateAdaptive([&](double t) { return metricSpeed(c, cs, t, hint); }, a, b, tolerance);
}

std::vector<double> discretizeCurve(const Curve& c, const ControlSpace& cs, int minSegments,
                                    const DiscretizeOptions& options) {
  int hint = -1;
  const Integrand f = [&](double t) { return metricSpeed(c, cs, t, hint); };
  const std::vector<double> bounds = pieceBounds(c);

  std::vector<Piece> pieces;
  std::int64_t total = 0;
  for (size_t k = 0; k + 1 < bounds.size(); ++k) {
    Piece p{bounds[k], bounds[k + 1], {}, 0.0, 1};
    const double w = p.b - p.a;
    collectLeaves(f, p.a, p.b, gaussLegendre5(f, p.a, p.b), options.tolerance, options.absoluteTolerance, w / 16.0, 24,
                  &p.leaves);
    for (const Leaf& l : p.leaves) p.length += l.value;
    require(std::isfinite(p.length), ErrorCode::InvalidMetric,
            std::string("metric length of a ") + c.typeName() + " curve is not finite");
    const double n = std::max(1.0, std::round(p.length));
    require(n <= double(options.maxSegments), ErrorCode::ElementBudgetExceeded,
            std::string("discretizing a ") + c.typeName() + " curve of metric length " + std::to_string(p.length) +
                " would exceed the budget of " + std::to_string(options.maxSegments) + " boundary segments");
    p.segments = int(n);
    total += p.segments;
    require(total <= options.maxSegments, ErrorCode::ElementBudgetExceeded,
            std::string("discretizing a ") + c.typeName() + " curve needs more than the budget of " +
                std::to_string(options.maxSegments) + " boundary segments");
    pieces.push_back(std::move(p));
  }
  // Too few segments in total: add them where the segments are longest in the metric.
  while (total < minSegments) {
    auto it = std::max_element(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) {
      return x.length / x.segments < y.length / y.segments;
    });
    ++it->segments;
    ++total;
  }

  std::vector<double> ts{0.0};
  for (const Piece& p : pieces) {
    size_t leaf = 0;
    double cum = 0.0;  // metric length up to leaves[leaf].a
    for (int k = 1; k < p.segments; ++k) {
      const double target = p.length * k / p.segments;
      while (leaf + 1 < p.leaves.size() && cum + p.leaves[leaf].value < target) cum += p.leaves[leaf++].value;
      ts.push_back(std::max(ts.back(), invertInLeaf(f, p.leaves[leaf], cum, target)));
    }
    ts.push_back(p.b);
  }
  return ts;
}

namespace {
// Straight between its discretization points (a line, a polyline keeping its vertices): the
// segment's midpoint is then the straight one, bit for bit.
bool isStraightBetweenPoints(const Curve& c) {
  if (dynamic_cast<const LineCurve*>(&c)) return true;
  const auto* poly = dynamic_cast<const PolylineCurve*>(&c);
  return poly && poly->breakpoints().size() + 2 == poly->points().size();
}
}  // namespace

std::vector<std::vector<BoundaryLoop>> discretizeDomains(const std::vector<const Domain*>& faces,
                                                         const ControlSpace& cs, const DiscretizeOptions& options) {
  // Minimum segment count per curve: a closed contour must have at least 3 segments.
  std::map<const Curve*, int> minimum;
  // Curves in order of first use: iterating `minimum` would follow heap addresses,
  // which differ between runs and platforms, and the query cache of the control
  // space makes metric queries depend on their order.
  std::vector<const Curve*> curveOrder;
  auto contoursOf = [](const Domain& d) {
    std::vector<const Contour*> cs{&d.outer};
    for (const Contour& h : d.holes) cs.push_back(&h);
    return cs;
  };
  for (const Domain* face : faces)
    for (const Contour* contour : contoursOf(*face)) {
      const int n = int(contour->curves.size());
      const int need = n == 1 ? options.minSegmentsClosedCurve : n == 2 ? 2 : 1;
      for (const CurveUse& u : contour->curves) {
        const Curve* c = u.curve.get();
        if (!minimum.count(c)) curveOrder.push_back(c);
        minimum[c] = std::max(minimum[c], need);
      }
    }

  std::map<const Curve*, std::vector<Vec2>> points;     // discretized once, shared by every use
  std::map<const Curve*, std::vector<Vec2>> midpoints;  // of each segment, on the curve
  auto discretizeOne = [&](const Curve* c) {
    const std::vector<double> ts = discretizeCurve(*c, cs, minimum[c], options);
    std::vector<Vec2> pts, mids;
    for (double t : ts) pts.push_back(c->point(t));
    for (size_t j = 0; j + 1 < ts.size(); ++j)
      mids.push_back(isStraightBetweenPoints(*c) ? Vec2(0.5 * (pts[j] + pts[j + 1]))
                                                 : c->point(0.5 * (ts[j] + ts[j + 1])));
    points[c] = std::move(pts);
    midpoints[c] = std::move(mids);
  };
  auto checkBudget = [&] {
    std::int64_t total = 0;
    for (const auto& e : points) total += std::int64_t(e.second.size()) - 1;
    require(total <= options.maxSegments, ErrorCode::ElementBudgetExceeded,
            "the contour discretization exceeds the budget of " + std::to_string(options.maxSegments) +
                " boundary segments");
  };
  // Estimate before work: every smooth piece (a polyline keeps its vertices) is at least one
  // segment, so a contour with more pieces than the budget is refused before any quadrature.
  std::int64_t leastSegments = 0;
  for (const Curve* c : curveOrder)
    leastSegments += std::max<std::int64_t>(minimum[c], std::int64_t(pieceBounds(*c).size()) - 1);
  require(leastSegments <= options.maxSegments, ErrorCode::ElementBudgetExceeded,
          "the contour discretization needs at least " + std::to_string(leastSegments) +
              " boundary segments (curve pieces and polyline vertices), over the budget of " +
              std::to_string(options.maxSegments) + " boundary segments");
  for (const Curve* c : curveOrder) discretizeOne(c);
  checkBudget();

  // Chained points of one contour, and the curve of each of its segments.
  auto assemble = [&](const Contour& contour, BoundaryLoop* loop, std::vector<const Curve*>* owner) {
    for (const CurveUse& u : contour.curves) {
      std::vector<Vec2> pts = points.at(u.curve.get());
      std::vector<Vec2> mids = midpoints.at(u.curve.get());
      if (u.reversed) std::reverse(pts.begin(), pts.end()), std::reverse(mids.begin(), mids.end());
      // The last point is the next curve's first point.
      loop->points.insert(loop->points.end(), pts.begin(), pts.end() - 1);
      loop->edgeMidpoints.insert(loop->edgeMidpoints.end(), mids.begin(), mids.end());
      loop->edgeRefs.insert(loop->edgeRefs.end(), pts.size() - 1, u.curve->ref());
      if (owner) owner->insert(owner->end(), pts.size() - 1, u.curve.get());
    }
  };

  // Chords of nearby curves may cross although the curves do not: refine both curves
  // (double their segments) until the polygons are clean (section 3.2 "invalid contour").
  if (options.refineCrossings)
    for (int round = 0;; ++round) {
      bool refined = false;
      for (const Domain* face : faces) {
        std::vector<std::vector<Vec2>> polygons;
        std::vector<std::vector<const Curve*>> owners;
        for (const Contour* contour : contoursOf(*face)) {
          BoundaryLoop loop;
          owners.emplace_back();
          assemble(*contour, &loop, &owners.back());
          polygons.push_back(std::move(loop.points));
        }
        PolygonCrossing x;
        if (!findPolygonCrossing(polygons, &x)) continue;
        require(round < options.maxRefinementRounds, ErrorCode::SelfIntersectingContour,
                "the boundary discretization crosses itself near " + formatPoint(x.where) + " even after " +
                    std::to_string(round) +
                    " refinements: curves too close for the requested metric, or crossing curves");
        for (const Curve* c :
             {owners[size_t(x.polygonA)][size_t(x.segmentA)], owners[size_t(x.polygonB)][size_t(x.segmentB)]}) {
          minimum[c] = std::max(minimum[c], 2 * int(points[c].size() - 1));
          discretizeOne(c);
        }
        checkBudget();
        refined = true;
      }
      if (!refined) break;
    }

  std::vector<std::vector<BoundaryLoop>> result;
  for (const Domain* face : faces) {
    std::vector<BoundaryLoop> loops;
    const auto contours = contoursOf(*face);
    for (size_t k = 0; k < contours.size(); ++k) {
      BoundaryLoop loop;
      assemble(*contours[k], &loop, nullptr);
      // Outer counter-clockwise, holes clockwise.
      const bool ccw = signedArea(loop.points) > 0;
      if (ccw != (k == 0)) {
        const int n = int(loop.points.size());
        BoundaryLoop rev;
        for (int i = 0; i < n; ++i) {
          rev.points.push_back(loop.points[size_t(n - 1 - i)]);
          const size_t e = size_t(((n - 2 - i) % n + n) % n);
          rev.edgeRefs.push_back(loop.edgeRefs[e]);
          rev.edgeMidpoints.push_back(loop.edgeMidpoints[e]);
        }
        loop = std::move(rev);
      }
      loops.push_back(std::move(loop));
    }
    result.push_back(std::move(loops));
  }
  return result;
}

std::vector<BoundaryLoop> discretizeDomain(const Domain& domain, const ControlSpace& cs,
                                           const DiscretizeOptions& options) {
  return discretizeDomains({&domain}, cs, options).front();
}

}  // namespace anisomesh

#include "anisomesh/pipeline/element_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

// The contours of a domain as straight edges, bucketed by horizontal bands so that an
// even-odd point-in-domain test scans only the edges of the point's band.
class DomainRaster {
 public:
  explicit DomainRaster(const Domain& domain) {
    addContour(domain.outer);
    for (const Contour& h : domain.holes) addContour(h);
    if (edges_.empty()) return;
    lo_ = hi_ = edges_[0].a.y();
    for (const Edge& e : edges_) {
      lo_ = std::min({lo_, e.a.y(), e.b.y()});
      hi_ = std::max({hi_, e.a.y(), e.b.y()});
    }
    bands_ = int(std::clamp(2.0 * std::sqrt(double(edges_.size())), 16.0, 4096.0));
    const double span = hi_ - lo_;
    step_ = span > 0 && std::isfinite(span) ? span / bands_ : 0.0;
    start_.assign(size_t(bands_) + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<int> fill(start_.begin(), start_.end() - 1);
      for (int i = 0; i < int(edges_.size()); ++i) {
        const int b0 = band(std::min(edges_[i].a.y(), edges_[i].b.y()));
        const int b1 = band(std::max(edges_[i].a.y(), edges_[i].b.y()));
        for (int b = b0; b <= b1; ++b) {
          if (pass == 0)
            ++start_[size_t(b) + 1];
          else
            items_[size_t(fill[size_t(b)]++)] = i;
        }
      }
      if (pass == 0) {
        for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
        items_.resize(size_t(start_.back()));
      }
    }
  }

  // Even-odd rule over the outer contour and the holes.
  bool inside(const Vec2& p) const {
    if (edges_.empty() || !(p.y() >= lo_ && p.y() <= hi_)) return false;
    const int b = band(p.y());
    bool in = false;
    for (int k = start_[size_t(b)]; k < start_[size_t(b) + 1]; ++k) {
      const Edge& e = edges_[size_t(items_[size_t(k)])];
      if ((e.a.y() > p.y()) == (e.b.y() > p.y())) continue;
      const double x = e.a.x() + (p.y() - e.a.y()) / (e.b.y() - e.a.y()) * (e.b.x() - e.a.x());
      if (p.x() < x) in = !in;
    }
    return in;
  }

 private:
  struct Edge {
    Vec2 a, b;
  };

  int band(double y) const {
    if (!(step_ > 0)) return 0;
    const double t = (y - lo_) / step_;
    if (!(t >= 0)) return 0;
    return t >= bands_ - 1 ? bands_ - 1 : int(t);
  }

  // A curve as a chain of points: its breakpoints, plus samples on curved pieces.
  void addContour(const Contour& c) {
    for (const CurveUse& u : c.curves) {
      const Curve& curve = *u.curve;
      std::vector<double> ts{0.0};
      for (double t : curve.breakpoints())
        if (t > ts.back() && t < 1.0) ts.push_back(t);
      ts.push_back(1.0);
      const bool straight =
          std::strcmp(curve.typeName(), "line") == 0 || std::strcmp(curve.typeName(), "polyline") == 0;
      const int per = straight ? 1 : std::max(1, 64 / int(ts.size() - 1));
      Vec2 prev = curve.point(0.0);
      for (size_t k = 0; k + 1 < ts.size(); ++k)
        for (int j = 1; j <= per; ++j) {
          const Vec2 q = curve.point(ts[k] + (ts[k + 1] - ts[k]) * j / per);
          edges_.push_back({prev, q});
          prev = q;
        }
    }
  }

  std::vector<Edge> edges_;
  double lo_ = 0.0, hi_ = 0.0, step_ = 0.0;
  int bands_ = 1;
  std::vector<int> start_, items_;
};

}  // namespace

double estimateElementCount(const Domain& domain, const AdaptiveControlSpace& cs) {
  const DomainRaster raster(domain);
  double area = 0.0;  // metric area of the domain
  for (const std::vector<int>& nodes : cs.elementNodes()) {
    if (nodes.size() < 3) continue;
    Vec2 centre = Vec2::Zero();
    double a = 0.0;
    for (size_t k = 0; k < nodes.size(); ++k) {
      const Vec2& p = cs.nodePosition(nodes[k]);
      const Vec2& q = cs.nodePosition(nodes[(k + 1) % nodes.size()]);
      a += p.x() * q.y() - p.y() * q.x();
      centre += p;
    }
    centre /= double(nodes.size());
    if (!raster.inside(centre)) continue;
    const Mat2 m = cs.metricAt(centre).tensor();
    const double det = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
    area += 0.5 * std::fabs(a) * std::sqrt(std::max(0.0, det));
  }
  return area / (std::sqrt(3.0) / 4.0);
}

double elementCountBound(const AdaptiveControlSpace& cs) {
  double largest = 0.0;  // the largest |eigenvalue| of a node's Mt
  // |mean| + radius of the eigenvalues, with sqrt instead of the portable hypot (a tenth of
  // the cost on a drag's every run): within an ulp, which the 1.0001 margin covers; an
  // overflow gives infinity, and the estimate decides.
  for (int i = 0; i < cs.nodeCount(); ++i) {
    const SymMt& m = cs.nodeMt(i);
    const double mean = 0.5 * (m.a + m.c), half = 0.5 * (m.a - m.c);
    const double l = std::fabs(mean) + std::sqrt(half * half + m.b * m.b);
    if (!(l < INFINITY)) return INFINITY;  // (a NaN node too: std::max would drop it)
    largest = std::max(largest, l);
  }
  const Vec2 size = cs.bounds().size();
  const double l = 4.0 * largest;  // (weights' absolute sum: 1 bilinear, at most 3 serendipity)
  return 1.0001 * std::fabs(size.x() * size.y()) * l * l / (std::sqrt(3.0) / 4.0);
}

void checkElementEstimate(const Domain& domain, const AdaptiveControlSpace& cs, std::int64_t maxElements,
                          const char* stage, const ElementEstimateOptions& options) {
  // Far below the budget even at the finest node's size everywhere: the estimate (a query
  // per control element) cannot exceed it. (NaN and infinite bounds take the estimate.)
  if (elementCountBound(cs) <= options.slack * double(maxElements)) return;
  const double estimate = estimateElementCount(domain, cs);
  if (!(estimate > options.slack * double(maxElements))) return;
  std::ostringstream os;
  os.precision(3);
  os << stage << ": the metric asks for about " << estimate << " elements, above the element budget of " << maxElements
     << " (estimated from the control space before the work)";
  throw Error(ErrorCode::ElementBudgetExceeded, os.str());
}

}  // namespace anisomesh

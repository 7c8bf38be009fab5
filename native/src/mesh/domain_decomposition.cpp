// Planar domain decomposition: recursive bisection at the metric-area median by chords
// between boundary points, straight or along principal lines (see mesh/domain_decomposition.h).
#include "anisomesh/mesh/domain_decomposition.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "anisomesh/boundary/discretize.h"
#include "anisomesh/controlspace/concurrency.h"
#include "anisomesh/core/bucket_grid.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/geometry/curve.h"
#include "anisomesh/geometry/domain.h"
#include "anisomesh/mesh/predicates.h"
#include "anisomesh/metric/sym_eigen.h"
#include "principal_line.h"

namespace anisomesh {
namespace {

constexpr double kTriangleArea = 0.43301270189221932;  // sqrt(3) / 4: a unit equilateral triangle
// Cut positions tried: the median first, then half a sample column further each way, up
// to a quarter of the part's extent (a layer crossing the median obliquely is avoided
// where it runs square to the cut: a sinusoidal front is cut at its crests).
constexpr double kCutStep = 0.5;
constexpr double kCutReach = 0.25;
// Chords through anisotropic metric (aspect ratio above kAlignAspect) must run within
// kAlignAngle of a principal direction: chords are boundaries to the parts, and a chord
// crossing a strongly stretched layer obliquely costs quality next to it. The rule came in
// when the mesher left sliver fans along such boundaries (min Q 0.01; fixed since by swap
// sweeps that run to the end). With 10 degrees instead of 2, straight cuts split the
// front case of remesh_throughput.mjs at 1e6 into 27 parts and its min Q drops from 0.73
// to 0.52; cuts along principal lines split it into 64 at min Q 0.70.
constexpr double kAlignAspect = 1.5;
constexpr double kAlignAngle = 0.035;  // radians, 2 degrees
constexpr int kAlignSamples = 32;      // metric samples along a chord
// Cuts along principal lines: integration steps per part extent, seeds tried (across
// positions on the median line and on the sample columns one and two either side of it),
// and the least share of the part's metric area either side must get.
constexpr int kTraceSteps = 256;
constexpr double kSeedAcross[] = {0.5, 0.3, 0.7};
constexpr int kSeedColumns = 3;
constexpr double kTracedBalance = 0.2;

struct Edge {
  int a, b, ref;
  char chord;
};

// A chord between boundary points a and b; inner holds its points between them once it
// is discretized (a straight chord is discretized when its cut is taken).
struct Chord {
  int a, b;
  std::vector<Vec2> inner;
  bool discretized = false;
};

// Splits parts of the decomposition under way: reads the points so far (ids below their
// count), numbers the chord points it adds after them.
class Decomposer {
 public:
  Decomposer(const ControlSpace& cs, const DomainDecompositionOptions& o, const std::vector<Vec2>& points)
      : cs_(cs), o_(o), base_(points), baseSize_(static_cast<int>(points.size())) {}

  // The chord points added by the cuts taken, in id order from the points' count on.
  std::vector<Vec2>& added() { return added_; }

  // Cut lines run along the frame's axes: columns of frame are unit vectors (physical).
  void setFrame(const Mat2& frame) { frame_ = frame; }

  // Metric-area samples of a part along its longer box side: columns of det(Mt) times area.
  struct Samples {
    int axis = 0;
    double lo = 0.0, width = 0.0;
    std::vector<double> column;
    double total = 0.0;
    Mat2 stretch = Mat2::Zero();  // sum of area x (1 - 1/aspect) x e e^T, e the small-size direction
  };

  // withStretch: s.stretch too (only the whole domain's frame needs it; the splits do not).
  Samples sample(const std::vector<Edge>& edges, int axis = -1, bool withStretch = false) const {
    Samples s;
    const std::vector<Vec2> ends = localEnds(edges);  // each edge's a, then its b
    Vec2 lo = ends[0], hi = lo;
    for (size_t k = 0; k < edges.size(); ++k) lo = lo.cwiseMin(ends[2 * k]), hi = hi.cwiseMax(ends[2 * k]);
    const Vec2 size = hi - lo;
    s.axis = axis >= 0 ? axis : (size.y() > size.x() ? 1 : 0);
    const int across = 1 - s.axis;
    const int nc = std::max(4, o_.gridSide), nr = std::max(4, o_.gridSide / 4);
    s.lo = lo[s.axis];
    s.width = size[s.axis] / nc;
    const double dr = size[across] / nr;
    s.column.assign(nc, 0.0);
    if (!(s.width > 0.0) || !(dr > 0.0)) return s;
    std::vector<double> xs;
    int hint = -1;  // the samples of a row follow each other: hinted queries
    for (int r = 0; r < nr; ++r) {
      const double y = lo[across] + (r + 0.5) * dr;
      xs.clear();
      for (size_t k = 0; k < edges.size(); ++k) {
        const Vec2 &p = ends[2 * k], &q = ends[2 * k + 1];
        if ((p[across] > y) != (q[across] > y))
          xs.push_back(p[s.axis] + (y - p[across]) / (q[across] - p[across]) * (q[s.axis] - p[s.axis]));
      }
      std::sort(xs.begin(), xs.end());
      for (size_t k = 0; k + 1 < xs.size(); k += 2) {
        const double xa = xs[k], xb = xs[k + 1];
        for (int j = std::max(0, static_cast<int>((xa - s.lo) / s.width)); j < nc; ++j) {
          const double c0 = std::max(xa, s.lo + j * s.width), c1 = std::min(xb, s.lo + (j + 1) * s.width);
          if (c0 >= xb) break;
          if (c1 <= c0) continue;
          Vec2 p;
          p[s.axis] = 0.5 * (c0 + c1);
          p[across] = y;
          const Mat2 mt = cs_.metricAtNear(frame_ * p, hint).transform();
          const double d = mt.determinant();
          if (!std::isfinite(d)) continue;
          const double w = (c1 - c0) * dr * std::fabs(d);
          s.column[j] += w;
          if (!withStretch) continue;
          const SymEigen2 e = symEigen(mt);
          if (e.l2 > 0.0) {
            const Vec2 dir(pm::cos(e.theta), pm::sin(e.theta));
            s.stretch += w * (1.0 - e.l2 / e.l1) * dir * dir.transpose();
          }
        }
      }
    }
    for (double c : s.column) s.total += c;
    return s;
  }

  // Splits a part in two or more; empty when no valid cut was found. Straight cuts across
  // the longer side first, then across the other; then cuts along lines of principal
  // directions, in the same order (a curved layer, which no straight cut meets square).
  std::vector<DomainPart> split(const DomainPart& part) {
    const std::vector<Edge> edges = edgesOf(part);
    const Samples first = sample(edges);
    std::vector<DomainPart> parts = splitAlong(edges, first);
    if (!parts.empty()) return parts;
    const Samples second = sample(edges, 1 - first.axis);
    parts = splitAlong(edges, second);
    if (!parts.empty()) return parts;
    const EdgeIndex index = indexOf(edges);
    parts = splitTraced(edges, index, first);
    if (parts.empty()) parts = splitTraced(edges, index, second);
    return parts;
  }

 private:
  // The median of the metric area along the samples' axis, interpolated inside its column.
  static double medianOf(const Samples& s) {
    double cum = 0.0;
    for (size_t j = 0; j < s.column.size(); ++j) {
      if (cum + s.column[j] >= 0.5 * s.total) {
        const double f = s.column[j] > 0.0 ? (0.5 * s.total - cum) / s.column[j] : 0.5;
        return s.lo + (static_cast<double>(j) + f) * s.width;
      }
      cum += s.column[j];
    }
    return s.lo + 0.5 * s.width * s.column.size();
  }

  std::vector<DomainPart> splitAlong(const std::vector<Edge>& edges, const Samples& s) {
    if (!(s.total > 0.0) || !std::isfinite(s.total)) return {};
    const double median = medianOf(s);
    const std::vector<Vec2> ends = localEnds(edges);  // for every position tried
    const int tries = 1 + 2 * static_cast<int>(kCutReach * static_cast<double>(s.column.size()) / kCutStep);
    for (int k = 0; k < tries; ++k) {
      const int step = (k + 1) / 2 * (k % 2 == 1 ? 1 : -1);  // 0, +1, -1, +2, -2, ...
      std::vector<DomainPart> parts = cutAt(edges, ends, s.axis, median + kCutStep * step * s.width);
      if (!parts.empty()) return parts;
    }
    return {};
  }

  // A part's edges bucketed by box, and its box in the frame's coordinates.
  struct EdgeIndex {
    Vec2 lo, hi;
    BucketGrid grid;
  };

  EdgeIndex indexOf(const std::vector<Edge>& edges) const {
    Vec2 lo = local(pt(edges[0].a)), hi = lo;
    std::vector<Box2> boxes;
    Box2 all{pt(edges[0].a), pt(edges[0].a)};
    for (const Edge& e : edges) {
      lo = lo.cwiseMin(local(pt(e.a))), hi = hi.cwiseMax(local(pt(e.a)));
      Box2 b{pt(e.a).cwiseMin(pt(e.b)), pt(e.a).cwiseMax(pt(e.b))};
      all.lo = all.lo.cwiseMin(b.lo), all.hi = all.hi.cwiseMax(b.hi);
      boxes.push_back(b);
    }
    return {lo, hi, BucketGrid(all, boxes)};
  }

  // A cut along the principal line through a seed near the metric-area median: it runs
  // along or across the stretching everywhere, as no straight cut through a curved layer can.
  std::vector<DomainPart> splitTraced(const std::vector<Edge>& edges, const EdgeIndex& index, const Samples& s) {
    if (!(s.total > 0.0) || !std::isfinite(s.total)) return {};
    const double median = medianOf(s);
    const int across = 1 - s.axis;
    const Vec2 &lo = index.lo, &hi = index.hi;
    const BucketGrid& grid = index.grid;
    mesh_internal::PrincipalLineOptions o;
    o.step = (hi - lo).maxCoeff() / kTraceSteps;
    o.maxSteps = 4 * kTraceSteps;
    o.isotropicAspect = kAlignAspect;
    for (int k = 0; k < 2 * kSeedColumns - 1; ++k) {
      const int column = (k + 1) / 2 * (k % 2 == 1 ? 1 : -1);  // 0, +1, -1, ...
      for (double f : kSeedAcross) {
        Vec2 q;
        q[s.axis] = median + column * s.width;
        q[across] = lo[across] + f * (hi[across] - lo[across]);
        const Vec2 seed = frame_ * q;
        if (!inside(edges, seed)) continue;
        std::vector<Chord> chords;
        if (!tracedChord(edges, grid, seed, frame_.col(across), o, chords)) continue;
        const size_t base = added_.size();
        std::vector<DomainPart> parts = cutWith(edges, chords);
        if (parts.size() == 2) {
          const double a0 = sample(edgesOf(parts[0])).total;  // the other side: the rest of s.total
          if (std::min(a0, s.total - a0) >= kTracedBalance * s.total) return parts;
        }
        added_.resize(base);
      }
    }
    return {};
  }

  // The chord along the principal line through seed, its ends moved to the nearer end
  // point of the boundary edge it leaves by, discretized at unit metric length; false
  // when it is not a valid chord (see chordsAt) or leaves the principal directions.
  bool tracedChord(const std::vector<Edge>& edges, const BucketGrid& grid, const Vec2& seed, const Vec2& along,
                   const mesh_internal::PrincipalLineOptions& o, std::vector<Chord>& out) const {
    auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
    const mesh_internal::RegionExit exit = [&](const Vec2& p, const Vec2& q, double& t, int& id) {
      const Vec2 r = q - p;
      t = 2.0;
      grid.any(Box2{p.cwiseMin(q), p.cwiseMax(q)}, [&](int k) {
        const Vec2 &u = pt(edges[k].a), w = pt(edges[k].b) - u;
        const double den = cross(r, w);
        if (den == 0.0) return false;
        const double tk = cross(u - p, w) / den, sk = cross(u - p, r) / den;
        if (tk >= 0.0 && tk <= 1.0 && sk >= 0.0 && sk <= 1.0 && tk < t) t = tk, id = k;
        return false;
      });
      return t <= 1.0;
    };
    const mesh_internal::PrincipalLine line = mesh_internal::tracePrincipalLine(cs_, seed, along, exit, o);
    if (line.points.size() < 3) return false;
    auto square = [&](const Vec2& x, const Vec2& from, int k) {  // the exit at x, coming from 'from', across edge k
      const Vec2 w = pt(edges[k].b) - pt(edges[k].a);
      return wideAngle(x, from - x, w) && wideAngle(x, from - x, -w);  // both angles it makes with the edge
    };
    const size_t last = line.points.size() - 1;
    if (!square(line.points[0], line.points[1], line.firstExit) ||
        !square(line.points[last], line.points[last - 1], line.lastExit))
      return false;
    auto snap = [&](int k, const Vec2& x) {
      const Edge& e = edges[k];
      return (x - pt(e.a)).squaredNorm() <= (x - pt(e.b)).squaredNorm() ? e.a : e.b;
    };
    Chord ch{snap(line.firstExit, line.points.front()), snap(line.lastExit, line.points.back()), {}, true};
    if (ch.a == ch.b) return false;
    // The line bent onto the end points: each end's move spread linearly over its length
    // (moving the end pieces alone would turn them off the principal directions).
    std::vector<double> arc(line.points.size(), 0.0);
    for (size_t i = 1; i < arc.size(); ++i) arc[i] = arc[i - 1] + (line.points[i] - line.points[i - 1]).norm();
    const Vec2 moveA = pt(ch.a) - line.points.front(), moveB = pt(ch.b) - line.points.back();
    std::vector<Vec2> path{pt(ch.a)};
    for (size_t i = 1; i + 1 < arc.size(); ++i) {
      const double f = arc[i] / arc.back();
      path.push_back(line.points[i] + (1.0 - f) * moveA + f * moveB);
    }
    path.push_back(pt(ch.b));
    const PolylineCurve curve(path, 0, false);
    const std::vector<double> t = discretizeCurve(curve, cs_, 1);
    std::vector<Vec2> poly{pt(ch.a)};
    for (size_t j = 1; j + 1 < t.size(); ++j) poly.push_back(curve.point(t[j]));
    poly.push_back(pt(ch.b));
    // Every piece: aligned, crossing no edge (but at its own end points) and no other piece.
    const size_t n = poly.size() - 1;
    std::vector<Box2> pieceBoxes;
    int hint = -1;  // the pieces follow each other
    for (size_t i = 0; i < n; ++i) {
      const Vec2 &p = poly[i], &q = poly[i + 1];
      if (!alignedAt(0.5 * (p + q), (q - p).normalized(), hint)) return false;
      const Box2 box{p.cwiseMin(q), p.cwiseMax(q)};
      const bool meets = grid.any(box, [&](int k) {
        const Edge& e = edges[k];
        const bool atA = i == 0 && (e.a == ch.a || e.b == ch.a), atB = i + 1 == n && (e.a == ch.b || e.b == ch.b);
        if (atA && atB) return true;  // the chord is an edge's twin
        if (atA && !wideAngle(p, q - p, pt(e.a == ch.a ? e.b : e.a) - p)) return true;
        if (atB && !wideAngle(q, p - q, pt(e.a == ch.b ? e.b : e.a) - q)) return true;
        return !atA && !atB && segmentsMeet(p, q, pt(e.a), pt(e.b));
      });
      if (meets) return false;
      pieceBoxes.push_back(box);
    }
    Box2 span{poly[0], poly[0]};
    for (const Box2& b : pieceBoxes) span.lo = span.lo.cwiseMin(b.lo), span.hi = span.hi.cwiseMax(b.hi);
    const BucketGrid own(span, pieceBoxes);
    for (size_t i = 0; i < n; ++i) {
      const bool meets = own.any(pieceBoxes[i], [&](int j) {
        const size_t u = static_cast<size_t>(j);
        return u + 1 < i || u > i + 1 ? segmentsMeet(poly[i], poly[i + 1], poly[u], poly[u + 1]) : false;
      });
      if (meets) return false;
    }
    ch.inner.assign(poly.begin() + 1, poly.end() - 1);
    out.clear();
    out.push_back(std::move(ch));
    return true;
  }

  static std::vector<Edge> edgesOf(const DomainPart& part) {
    std::vector<Edge> edges;
    for (size_t l = 0; l < part.loops.size(); ++l) {
      const auto& ids = part.loops[l];
      for (size_t i = 0; i < ids.size(); ++i)
        edges.push_back({ids[i], ids[(i + 1) % ids.size()], part.edgeRefs[l][i], part.chord[l][i]});
    }
    return edges;
  }

  // Segments [p, q] and [r, s] meet (touching included).
  static bool segmentsMeet(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s) {
    const double d1 = orient2d(p, q, r), d2 = orient2d(p, q, s), d3 = orient2d(r, s, p), d4 = orient2d(r, s, q);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    auto on = [](const Vec2& a, const Vec2& b, const Vec2& c) {  // c on [a, b], given collinear
      return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= c.y() &&
             c.y() <= std::max(a.y(), b.y());
    };
    return (d1 == 0 && on(p, q, r)) || (d2 == 0 && on(p, q, s)) || (d3 == 0 && on(r, s, p)) || (d4 == 0 && on(r, s, q));
  }

  // Even-odd containment of p in the edges' region.
  bool inside(const std::vector<Edge>& edges, const Vec2& p) const {
    bool in = false;
    for (const Edge& e : edges) {
      const Vec2 &a = pt(e.a), &b = pt(e.b);
      if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
        in = !in;
    }
    return in;
  }

  // The angle between u and v in the metric of point p is at least minChordAngle.
  bool wideAngle(const Vec2& p, const Vec2& u, const Vec2& v) const {
    const Mat2 m = cs_.metricAt(p).transform();
    const Vec2 mu = m * u, mv = m * v;
    const double c = mu.dot(mv) / (mu.norm() * mv.norm());
    return std::isfinite(c) && c < std::cos(o_.minChordAngle);
  }

  // Where the metric at p is anisotropic, the unit direction d runs near a principal direction.
  // (hint: the caller's query hint, for points that follow each other.)
  bool alignedAt(const Vec2& p, const Vec2& d, int& hint) const {
    const Mat2 mt = cs_.metricAtNear(p, hint).transform();
    const SymEigen2 v = symEigenValues(mt);  // the same l1, l2 as symEigen; its angle only when needed
    if (!(v.l2 > 0.0) || !std::isfinite(v.l1)) return false;
    if (v.l1 <= kAlignAspect * v.l2) return true;
    const SymEigen2 e = symEigen(mt);
    const Vec2 u(pm::cos(e.theta), pm::sin(e.theta));
    // |sin 2 theta| between d and u: zero along either principal direction.
    return 2.0 * std::fabs(d.dot(u) * (d.x() * u.y() - d.y() * u.x())) <= pm::sin(2.0 * kAlignAngle);
  }

  // Where the metric along [a, b] is anisotropic, the chord runs near a principal direction.
  bool aligned(const Vec2& a, const Vec2& b) const {
    const Vec2 d = (b - a).normalized();
    int hint = -1;  // the samples follow each other along the chord
    for (int k = 0; k < kAlignSamples; ++k)
      if (!alignedAt(a + (b - a) * ((k + 0.5) / kAlignSamples), d, hint)) return false;
    return true;
  }

  // p in the frame's coordinates.
  Vec2 local(const Vec2& p) const { return frame_.transpose() * p; }

  // The edges' end points in the frame's coordinates: edge k's a at 2 k, its b at 2 k + 1.
  std::vector<Vec2> localEnds(const std::vector<Edge>& edges) const {
    std::vector<Vec2> ends(2 * edges.size());
    for (size_t k = 0; k < edges.size(); ++k)
      ends[2 * k] = local(pt(edges[k].a)), ends[2 * k + 1] = local(pt(edges[k].b));
    return ends;
  }

  // The chords of the cut line {x[axis] = c} across the part, or empty when one is invalid
  // (framed: localEnds(edges)).
  std::vector<Chord> chordsAt(const std::vector<Edge>& edges, const std::vector<Vec2>& framed, int axis,
                              double c) const {
    const int across = 1 - axis;
    std::vector<std::pair<double, int>> crossings;  // (across coordinate, chosen end point)
    for (size_t k = 0; k < edges.size(); ++k) {
      const Edge& e = edges[k];
      const Vec2 &pa = framed[2 * k], &pb = framed[2 * k + 1];
      const double da = pa[axis] - c, db = pb[axis] - c;
      if (da == 0.0 || db == 0.0) return {};  // a point on the line: try another position
      if ((da > 0.0) == (db > 0.0)) continue;
      const double t = pa[across] + (-da) / (db - da) * (pb[across] - pa[across]);
      crossings.emplace_back(t, std::fabs(da) <= std::fabs(db) ? e.a : e.b);
    }
    if (crossings.size() < 2 || crossings.size() % 2 != 0) return {};
    std::sort(crossings.begin(), crossings.end());
    std::vector<Chord> chords;
    std::vector<int> ends;
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      if (crossings[k].first == crossings[k + 1].first) return {};
      chords.push_back({crossings[k].second, crossings[k + 1].second, {}, false});
      ends.push_back(crossings[k].second);
      ends.push_back(crossings[k + 1].second);
    }
    std::sort(ends.begin(), ends.end());
    if (std::adjacent_find(ends.begin(), ends.end()) != ends.end()) return {};  // shared end point
    for (const Chord& ch : chords)  // the cheap test first: many positions fail it
      if (!aligned(pt(ch.a), pt(ch.b))) return {};
    for (size_t k = 0; k < chords.size(); ++k) {
      const Chord& ch = chords[k];
      const Vec2 &a = pt(ch.a), &b = pt(ch.b);
      for (const Edge& e : edges) {
        const bool atA = e.a == ch.a || e.b == ch.a, atB = e.a == ch.b || e.b == ch.b;
        if (atA || atB) {
          // Edges at an end: not too sharp against the chord (this also rules out overlaps).
          if (atA && !wideAngle(a, b - a, pt(e.a == ch.a ? e.b : e.a) - a)) return {};
          if (atB && !wideAngle(b, a - b, pt(e.a == ch.b ? e.b : e.a) - b)) return {};
          if (atA && atB) return {};  // the chord is an edge's twin
          continue;
        }
        if (segmentsMeet(a, b, pt(e.a), pt(e.b))) return {};
      }
      for (size_t j = 0; j < k; ++j)
        if (segmentsMeet(a, b, pt(chords[j].a), pt(chords[j].b))) return {};
      if (!inside(edges, 0.5 * (a + b))) return {};
    }
    return chords;
  }

  // The faces of the part's edges and the chords (both ways), each a vertex cycle.
  struct Face {
    std::vector<int> directed;  // indices into the directed edge list
    double area = 0.0;
  };

  // Where w - v lies turning clockwise from du - v: 0 within (0, pi), 1 at pi, 2 within
  // (pi, 2 pi), 3 at 2 pi (along du - v itself).
  static int clockClass(const Vec2& v, const Vec2& du, const Vec2& w) {
    const double o = orient2d(v, du, w);
    if (o < 0) return 0;
    if (o > 0) return 2;
    return (w - v).dot(du - v) < 0 ? 1 : 3;
  }

  std::vector<DomainPart> cutAt(const std::vector<Edge>& edges, const std::vector<Vec2>& ends, int axis, double c) {
    std::vector<Chord> chords = chordsAt(edges, ends, axis, c);
    if (chords.empty()) return {};
    return cutWith(edges, chords);
  }

  // The parts the valid chords cut the part into (empty when the faces are not proper
  // parts); the chords' inner points are added to the points when the cut is taken.
  std::vector<DomainPart> cutWith(const std::vector<Edge>& edges, std::vector<Chord>& chords) {
    const size_t base = added_.size();
    std::vector<DomainPart> parts = walkFaces(edges, chords);
    if (parts.empty()) added_.resize(base);
    return parts;
  }

  std::vector<DomainPart> walkFaces(const std::vector<Edge>& edges, std::vector<Chord>& chords) {
    // Chords at unit metric length, their points numbered after the existing ones.
    std::vector<Edge> dir = edges;  // directed: the part's (domain on their left), then each chord both ways
    for (Chord& ch : chords) {
      if (!ch.discretized) {
        const LineCurve line(pt(ch.a), pt(ch.b));
        const std::vector<double> t = discretizeCurve(line, cs_, 1);
        for (size_t j = 1; j + 1 < t.size(); ++j) ch.inner.push_back(line.point(t[j]));
        ch.discretized = true;
      }
      std::vector<int> path{ch.a};
      for (const Vec2& p : ch.inner) {
        path.push_back(baseSize_ + static_cast<int>(added_.size()));
        added_.push_back(p);
      }
      path.push_back(ch.b);
      for (size_t i = 0; i + 1 < path.size(); ++i) dir.push_back({path[i], path[i + 1], 0, 1});
      for (size_t i = path.size() - 1; i > 0; --i) dir.push_back({path[i], path[i - 1], 0, 1});
    }
    std::vector<std::pair<int, int>> out;  // (source, directed edge) sorted by source
    out.reserve(dir.size());
    for (size_t i = 0; i < dir.size(); ++i) out.emplace_back(dir[i].a, static_cast<int>(i));
    std::sort(out.begin(), out.end());
    auto nextEdge = [&](int i) {  // the first outgoing edge clockwise from the reversed edge i
      const int v = dir[i].b, u = dir[i].a;
      auto it = std::lower_bound(out.begin(), out.end(), std::make_pair(v, -1));
      int best = -1, bestClass = 4;
      for (; it != out.end() && it->first == v; ++it) {
        const int j = it->second;
        const int cl = clockClass(pt(v), pt(u), pt(dir[j].b));
        if (best < 0 || cl < bestClass ||
            (cl == bestClass && (cl == 0 || cl == 2) && orient2d(pt(v), pt(dir[j].b), pt(dir[best].b)) < 0)) {
          best = j;
          bestClass = cl;
        }
      }
      return best;
    };
    std::vector<char> used(dir.size(), 0);
    std::vector<Face> faces;
    for (size_t start = 0; start < dir.size(); ++start) {
      if (used[start]) continue;
      Face f;
      int i = static_cast<int>(start);
      while (!used[i]) {
        used[i] = 1;
        f.directed.push_back(i);
        i = nextEdge(i);
        if (i < 0 || f.directed.size() > dir.size()) return {};
      }
      if (i != static_cast<int>(start)) return {};
      for (int j : f.directed) {
        const Vec2 &p = pt(dir[j].a), &q = pt(dir[j].b);
        f.area += p.x() * q.y() - p.y() * q.x();
      }
      std::vector<int> vs;
      for (int j : f.directed) vs.push_back(dir[j].a);
      std::sort(vs.begin(), vs.end());
      if (std::adjacent_find(vs.begin(), vs.end()) != vs.end()) return {};  // a pinched face
      faces.push_back(std::move(f));
    }
    std::vector<size_t> outer;
    for (size_t k = 0; k < faces.size(); ++k)
      if (faces[k].area > 0.0) outer.push_back(k);
    if (outer.size() < 2) return {};
    // Holes no chord touches belong to the face around them.
    std::vector<std::vector<size_t>> holes(outer.size());
    for (size_t k = 0; k < faces.size(); ++k) {
      if (faces[k].area > 0.0) continue;
      const Vec2& p = pt(dir[faces[k].directed[0]].a);
      int owner = -1;
      for (size_t o = 0; o < outer.size(); ++o) {
        std::vector<Edge> fe;
        for (int j : faces[outer[o]].directed) fe.push_back(dir[j]);
        if (inside(fe, p)) {
          if (owner >= 0) return {};
          owner = static_cast<int>(o);
        }
      }
      if (owner < 0) return {};
      holes[owner].push_back(k);
    }
    // Valid: write the parts.
    auto appendLoop = [&](const Face& f, DomainPart& p) {
      std::vector<int> ids, refs;
      std::vector<char> ch;
      for (int j : f.directed) {
        ids.push_back(dir[j].a);
        refs.push_back(dir[j].ref);
        ch.push_back(dir[j].chord);
      }
      p.loops.push_back(std::move(ids));
      p.edgeRefs.push_back(std::move(refs));
      p.chord.push_back(std::move(ch));
    };
    std::vector<DomainPart> parts(outer.size());
    for (size_t o = 0; o < outer.size(); ++o) {
      appendLoop(faces[outer[o]], parts[o]);
      for (size_t h : holes[o]) appendLoop(faces[h], parts[o]);
    }
    return parts;
  }

  const Vec2& pt(int id) const { return id < baseSize_ ? base_[id] : added_[id - baseSize_]; }

  const ControlSpace& cs_;
  const DomainDecompositionOptions& o_;
  const std::vector<Vec2>& base_;
  const int baseSize_;
  std::vector<Vec2> added_;
  Mat2 frame_ = Mat2::Identity();
};

}  // namespace

DomainParts decomposeDomain(const std::vector<BoundaryLoop>& loops, const ControlSpace& cs,
                            const DomainDecompositionOptions& options) {
  DomainParts out;
  DomainPart whole;
  bool usable = !loops.empty();
  for (const BoundaryLoop& l : loops) {
    usable = usable && l.points.size() >= 3 && l.edgeRefs.size() == l.points.size();
    for (const Vec2& p : l.points) usable = usable && p.allFinite();
  }
  for (size_t l = 0; usable && l < loops.size(); ++l) {
    const BoundaryLoop& lp = loops[l];
    const int n = static_cast<int>(lp.points.size()), base = static_cast<int>(out.points.size());
    out.points.insert(out.points.end(), lp.points.begin(), lp.points.end());
    std::vector<int> ids(n), refs(lp.edgeRefs);
    for (int i = 0; i < n; ++i) ids[i] = base + i;
    // The outer loop counter-clockwise, the holes clockwise: each edge has the domain on its left.
    const double area = signedArea(lp.points);
    usable = usable && area != 0.0 && std::isfinite(area);
    if ((l == 0) != (area > 0.0)) {
      std::reverse(ids.begin(), ids.end());  // edge k now joins old points n-1-k and n-2-k: old edge n-2-k
      for (int k = 0; k < n; ++k) refs[k] = lp.edgeRefs[(2 * n - 2 - k) % n];
    }
    whole.loops.push_back(std::move(ids));
    whole.edgeRefs.push_back(std::move(refs));
    whole.chord.emplace_back(n, 0);
  }
  out.loopPoints = static_cast<int>(out.points.size());
  if (!usable || options.partElements <= 0) {
    out.parts.push_back(std::move(whole));
    return out;
  }
  Decomposer d(cs, options, out.points);
  Mat2 frame = Mat2::Identity();
  std::vector<Edge> all;
  for (size_t l = 0; l < whole.loops.size(); ++l)
    for (size_t i = 0; i < whole.loops[l].size(); ++i)
      all.push_back({whole.loops[l][i], whole.loops[l][(i + 1) % whole.loops[l].size()], 0, 0});
  const Decomposer::Samples s = d.sample(all, -1, true);
  out.estimatedElements = s.total / kTriangleArea;
  // Cut along the dominant stretching (a rotated layer gets cuts along and across it);
  // within 1e-6 rad of the coordinate axes the frame stays exactly the identity.
  const Mat2& st = s.stretch;
  if (st(0, 1) != 0.0) {
    const double phi = 0.5 * pm::atan2(2.0 * st(0, 1), st(0, 0) - st(1, 1));
    const double off = phi - (M_PI / 2) * std::round(phi / (M_PI / 2));
    if (std::fabs(off) > 1e-6 && std::isfinite(off)) {
      frame << pm::cos(off), -pm::sin(off), pm::sin(off), pm::cos(off);
    }
  }
  int leaves = 1;
  while (2 * leaves <= options.maxParts &&
         2.0 * leaves * static_cast<double>(options.partElements) <= out.estimatedElements)
    leaves *= 2;
  out.parts.push_back(std::move(whole));
  // The parts of a level split independently (concurrently when the control space answers
  // concurrent queries); their chord points are numbered in part order afterwards, so the
  // ids are those of splitting the parts one after another.
  for (int level = 1; level < leaves; level *= 2) {
    const size_t n = out.parts.size();
    std::vector<std::vector<DomainPart>> pieces(n);
    std::vector<std::vector<Vec2>> added(n);
    auto splitPart = [&](size_t k) {
      Decomposer dk(cs, options, out.points);
      dk.setFrame(frame);
      pieces[k] = dk.split(out.parts[k]);
      added[k] = std::move(dk.added());
    };
    if (queriesAreConcurrent(cs)) {
      parallelChunks(n, 1, [&](size_t k, size_t, size_t) { splitPart(k); });
    } else {
      for (size_t k = 0; k < n; ++k) splitPart(k);
    }
    const int base = static_cast<int>(out.points.size());
    std::vector<DomainPart> next;
    for (size_t k = 0; k < n; ++k) {
      if (pieces[k].empty()) {
        next.push_back(std::move(out.parts[k]));
        continue;
      }
      const int shift = static_cast<int>(out.points.size()) - base;
      out.points.insert(out.points.end(), added[k].begin(), added[k].end());
      for (DomainPart& q : pieces[k]) {
        for (auto& loop : q.loops)
          for (int& id : loop) id += id >= base ? shift : 0;
        next.push_back(std::move(q));
      }
    }
    out.parts = std::move(next);
  }
  return out;
}

}  // namespace anisomesh

#pragma once
// Discrete metric sources of the paper (section 2.2, fig. 3), after Zhu [7]: a metric M
// held constant within distance r of a point, a segment or a curve piece, and plain
// nodes with a metric.
#include <functional>
#include <variant>
#include <vector>

#include "anisomesh/core/types.h"
#include "anisomesh/metric/metric.h"

namespace anisomesh {

// (P, M, r): M constant within radius r >= 0 of P.
struct RadialSource {
  Vec2 center{0.0, 0.0};
  Metric metric;
  double radius = 0.0;
};

// (P1, P2, M, r): M constant within distance r of the segment P1P2 (nonzero length).
struct SegmentSource {
  Vec2 a{0.0, 0.0};
  Vec2 b{1.0, 0.0};
  Metric metric;
  double radius = 0.0;
};

// (c(t), t1, t2, M, r): M constant within distance r of the curve piece c([t1, t2]).
// The curve is sampled into a polyline (adaptively, chord error below a fraction of the
// source's size), so it must be continuous on [t1, t2].
struct CurveSource {
  std::function<Vec2(double)> curve;
  double t1 = 0.0;
  double t2 = 1.0;
  Metric metric;
  double radius = 0.0;
};

// A curve already given as a polyline (the plain-data form of CurveSource, for JSON/wasm).
struct PolylineSource {
  std::vector<Vec2> points;
  Metric metric;
  double radius = 0.0;
};

// Discrete nodes with their own metrics (e.g. the nodes of another control space).
struct NodeSource {
  std::vector<Vec2> points;
  std::vector<Metric> metrics;
};

using MetricSource = std::variant<RadialSource, SegmentSource, CurveSource, PolylineSource, NodeSource>;

// A source reduced to its geometric primitive: the segment [a, b] (a == b for points)
// with metric and radius, plus the element size the structure must reach near it.
struct SourcePiece {
  Vec2 a{0.0, 0.0};
  Vec2 b{0.0, 0.0};
  Metric metric;
  double radius = 0.0;
  double targetSize = 0.0;  // max(radius, smallest size of metric) * sizeFactor
};

struct SourceOptions {
  double sizeFactor = 1.0;  // scales the element size required near a source
};

// Validates sources and reduces them to pieces. Throws InvalidArgument for a negative or
// non-finite radius or non-finite coordinates, ZeroLengthCurve for a zero-length segment,
// curve or polyline, InvalidArgument for nodes/metrics count mismatch. Pieces whose
// region (distance <= r) misses the box are dropped: a source entirely outside the
// domain is a no-op.
std::vector<SourcePiece> sourcePieces(const std::vector<MetricSource>& sources, const Box2& box,
                                      const SourceOptions& options = {});

// Distance between the segment ab (a == b allowed) and the box (0 when they meet).
double segmentBoxDistance(const Vec2& a, const Vec2& b, const Box2& box);

// Distance from p to the piece's segment.
double distanceToPiece(const SourcePiece& piece, const Vec2& p);

}  // namespace anisomesh

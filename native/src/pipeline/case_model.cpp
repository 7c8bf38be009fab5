#include "anisomesh/pipeline/case_model.h"

#include <utility>

namespace anisomesh {

// (emplace_back with in_place_type: push_back of a temporary variant trips GCC 12's
// false -Wmaybe-uninitialized.)
std::vector<MetricSource> discreteSources(const std::vector<SourceSpec>& sources) {
  std::vector<MetricSource> out;
  for (const SourceSpec& s : sources) {
    const Metric m = Metric::fromSizes(s.metric.alpha, s.metric.h1, s.metric.h2);
    switch (s.type) {
      case SourceType::Radial:
        out.emplace_back(std::in_place_type<RadialSource>, RadialSource{s.center, m, s.radius});
        break;
      case SourceType::Segment:
        out.emplace_back(std::in_place_type<SegmentSource>, SegmentSource{s.p1, s.p2, m, s.radius});
        break;
      case SourceType::Polyline:
        out.emplace_back(std::in_place_type<PolylineSource>, PolylineSource{s.points, m, s.radius});
        break;
      case SourceType::Curve: {
        CurveSource c;
        c.curve = [curve = s.curve](double t) { return curve->point(t); };
        c.t1 = s.t1;
        c.t2 = s.t2;
        c.metric = m;
        c.radius = s.radius;
        out.emplace_back(std::in_place_type<CurveSource>, std::move(c));
        break;
      }
      case SourceType::Nodes: {
        NodeSource n;
        n.points = s.points;
        for (const MetricSizes& z : s.metrics) n.metrics.push_back(Metric::fromSizes(z.alpha, z.h1, z.h2));
        out.emplace_back(std::in_place_type<NodeSource>, std::move(n));
        break;
      }
      case SourceType::Analytic:
        break;
    }
  }
  return out;
}

}  // namespace anisomesh

// Sources across a periodic seam: a patch shared with itself along two curves that differ by
// a constant shift in (u, v) (a sphere band's u = 0 and u = 2 pi, a torus's two pairs) is
// periodic there, and a source near one side reaches across to the other side.
#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

namespace {

Vec2 shifted(const Vec2& p, const Vec2& s) { return p + s; }

}  // namespace

std::vector<Vec2> seamShifts(const SurfaceModel& m, int patch) {
  std::vector<Vec2> periods;
  for (const SharedCurve& sc : m.shared) {
    if (sc.a.patch != patch || sc.b.patch != patch) continue;
    const Curve *a = curveAt(m, sc.a), *b = curveAt(m, sc.b);
    if (!a || !b) continue;
    // b's point at a's parameter t (a.start meets b.end when reversed) minus a's: a period
    // when it is the same at both ends and in the middle.
    auto gap = [&](double t) { return Vec2(b->point(sc.reversed ? 1.0 - t : t) - a->point(t)); };
    const Vec2 g = gap(0.0);
    const double tol = 1e-9 * std::max(1.0, g.norm());
    if (g.norm() > 0.0 && (gap(1.0) - g).norm() <= tol && (gap(0.5) - g).norm() <= tol) periods.push_back(g);
  }
  // Every combination of -1, 0, +1 of each period but none at all (a torus: 8 shifts).
  std::vector<Vec2> shifts{Vec2::Zero()};
  for (const Vec2& g : periods) {
    const size_t n = shifts.size();
    for (size_t i = 0; i < n; ++i) {
      shifts.push_back(shifts[i] + g);
      shifts.push_back(shifts[i] - g);
    }
  }
  shifts.erase(shifts.begin());
  return shifts;
}

std::vector<MetricSource> withSeamImages(const std::vector<MetricSource>& sources, const std::vector<Vec2>& shifts) {
  std::vector<MetricSource> out = sources;
  for (const Vec2& s : shifts)
    for (const MetricSource& src : sources) {
      MetricSource image = src;
      std::visit(
          [&](auto& x) {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, RadialSource>) {
              x.center = shifted(x.center, s);
            } else if constexpr (std::is_same_v<T, SegmentSource>) {
              x.a = shifted(x.a, s), x.b = shifted(x.b, s);
            } else if constexpr (std::is_same_v<T, CurveSource>) {
              x.curve = [f = x.curve, s](double t) { return shifted(f(t), s); };
            } else {  // PolylineSource, NodeSource
              for (Vec2& p : x.points) p = shifted(p, s);
            }
          },
          image);
      out.push_back(std::move(image));
    }
  return out;
}

}  // namespace surface_mesher
}  // namespace anisomesh

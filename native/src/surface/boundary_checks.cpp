// Surface meshing: section 3.2 checks of a patch boundary after its boundary-only
// triangulation (eps2 proximity, contour chord, eps1 and [1/2, 2] segment lengths).
#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

namespace {

SegmentSource segmentSource(const Vec2& a, const Vec2& b, const Metric& m, double r) {
  SegmentSource s;
  s.a = a;
  s.b = b;
  s.metric = m;
  s.radius = r;
  return s;
}

}  // namespace

// Section 3.2 on one patch after its boundary-only triangulation: proximity of boundaries
// (eps2), contour chords (curvature of the contour in 3D), boundary segment lengths (eps1).
void ModelMesher::checkPatchBoundary(int p) {
  const SurfacePatch& patch = m_.patches[size_t(p)];
  const Surface& surf = *patch.surface;
  const ControlSpace& cs = space(p);
  PlanarMesherOptions bo = o_.mesher;
  bo.boundaryOnly = true;
  bo.timings = nullptr;
  bo.progress = nullptr;
  const Mesh bm = meshPlanarBoundary(loopsOf(p, nullptr, nullptr), cs, bo);

  // Boundary vicinity (eps2 = 0.2): a triangle of small metric area whose vertex lies
  // within half a unit (metric) of the opposite boundary edge joins two boundary pieces
  // that are closer than the metric asks. Fans onto finely split edges and ears of a
  // contour (two boundary edges) are not proximity.
  std::set<std::array<int, 2>> bedges;
  for (const auto& e : bm.edges) bedges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  auto uvAt = [&](int i) { return bm.params.empty() ? Vec2(bm.points[size_t(i)].head<2>()) : bm.params[size_t(i)]; };
  for (const auto& tri : bm.triangles) {
    int onBoundary = 0, boundaryEdge = -1;
    for (int k = 0; k < 3; ++k) {
      const int i0 = tri[size_t(k)], i1 = tri[size_t((k + 1) % 3)];
      if (bedges.count({std::min(i0, i1), std::max(i0, i1)})) ++onBoundary, boundaryEdge = k;
    }
    if (onBoundary > 1) continue;
    const Vec2 a = uvAt(tri[0]), b = uvAt(tri[1]), c = uvAt(tri[2]);
    const Vec2 g = (a + b + c) / 3.0;
    const Metric m = cs.metricAt(g);
    const Vec2 e[3] = {m.apply(b - a), m.apply(c - b), m.apply(a - c)};
    const double area = 0.5 * std::abs(e[0].x() * e[1].y() - e[0].y() * e[1].x());
    if (!(area < 0.2)) continue;
    double gap;  // metric distance between the boundary pieces the triangle joins
    if (boundaryEdge >= 0)
      gap = 2.0 * area / e[boundaryEdge].norm();
    else
      gap = 2.0 * area / std::max({e[0].norm(), e[1].norm(), e[2].norm()});
    if (gap < 0.5) {
      const double uvLongest = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
      RadialSource src;
      src.center = g;
      src.metric = m.scaled(std::max(gap / 0.5, 0.25));
      src.radius = 0.5 * uvLongest;
      addSource(p, src);
    }
  }

  const double tol = o_.metric.chordTolerance;
  for (const auto& contourSlots : ps_[size_t(p)].slots)
    for (int si : contourSlots) {
      Slot& s = slots_[size_t(si)];
      const Slot* other = s.master >= 0     ? &slots_[size_t(s.master)]
                          : s.follower >= 0 ? &slots_[size_t(s.follower)]
                                            : nullptr;
      const int owner = s.master >= 0 ? s.master : si;  // the slot that gets re-discretized
      const size_t n = s.t.size();
      for (size_t i = 0; i + 1 < n; ++i) {
        const Vec2 u0 = uvOf(s, i), u1 = uvOf(s, i + 1), um = 0.5 * (u0 + u1);
        const double l = cs.metricAt(um).length(u1 - u0);
        double lOther = 0.0;
        if (other) {
          const size_t j =
              (s.master >= 0 ? s.masterReversed : slots_[size_t(s.follower)].masterReversed) ? n - 1 - i : i;
          const size_t j1 =
              (s.master >= 0 ? s.masterReversed : slots_[size_t(s.follower)].masterReversed) ? j - 1 : j + 1;
          const Vec2 v0 = uvOf(*other, j), v1 = uvOf(*other, j1);
          lOther = space(other->patch).metricAt(0.5 * (v0 + v1)).length(v1 - v0);
        }
        // Contour chord: the 3D chord against the 3D contour at the segment's middle parameter.
        const Vec3 x0 = surf.point(u0), x1 = surf.point(u1);
        const double tm = 0.5 * (s.t[i] + s.t[i + 1]);
        const Vec3 xm = surf.point(s.c->point(tm));
        const double dev = (xm - 0.5 * (x0 + x1)).norm();
        if (tol > 0 && dev > tol) {
          const double h = 0.9 * (u1 - u0).norm() * std::sqrt(tol / dev);
          const Vec2 d = u1 - u0;
          addSource(p,
                    segmentSource(u0, u1, Metric::fromSizes(pm::atan2(d.y(), d.x()), h, o_.metric.maxAspectRatio * h),
                                  0.5 * d.norm()));
          slots_[size_t(owner)].invalid = true;
        }
        // Segment length (eps1 = 0.8): refine near short segments, unless without adaptation
        // the shortness only comes from the neighbour's stricter metric.
        const bool neighbourMadeIt = other && lOther > l;
        // The segment's length is the reference along it; across it the metric stays as it is.
        if (l < 0.8 && (o_.adaptation || !neighbourMadeIt)) {
          const Vec2 d = u1 - u0;
          const Metric here = cs.metricAt(um);
          const double across = here.sizeAlong(Vec2(-d.y(), d.x()));
          addSource(
              p, segmentSource(u0, u1, Metric::fromSizes(pm::atan2(d.y(), d.x()), d.norm(), std::max(across, d.norm())),
                               0.25 * d.norm()));
        }
        const double lEff = std::max(l, lOther);
        if ((lEff < 0.5 && n > 2 && std::max<size_t>(n - 1, 1) > size_t(s.minSegments)) || lEff > 2.0)
          slots_[size_t(owner)].invalid = true;
      }
    }
}

}  // namespace surface_mesher

}  // namespace anisomesh

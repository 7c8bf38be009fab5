// Surface meshing: section 3.2 checks of a patch boundary after its boundary-only
// triangulation, by the rules and thresholds of the boundary area (boundary_updates.h)
// that planar cases use: eps2 proximity, contour chord (here in 3D), eps1 and
// [lengthMin, lengthMax] segment lengths.
#include "anisomesh/boundary/boundary_updates.h"
#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

// Section 3.2 on one patch after its boundary-only triangulation: proximity of boundaries
// (eps2), contour chords (curvature of the contour in 3D), boundary segment lengths (eps1).
void ModelMesher::checkPatchBoundary(int p) {
  const SurfacePatch& patch = m_.patches[size_t(p)];
  const Surface& surf = *patch.surface;
  const ControlSpace& cs = space(p);
  const BoundaryUpdateOptions& rules = o_.boundary;
  PlanarMesherOptions bo = o_.mesher;
  bo.boundaryOnly = true;
  bo.timings = nullptr;
  bo.progress = nullptr;
  bo.boundaryCache = boundaryCaches_[size_t(p)];
  const std::vector<BoundaryLoop> loops = loopsOf(p, nullptr, nullptr);
  const Mesh bm = meshPlanarBoundary(loops, cs, bo);

  std::vector<MetricSource> sources;
  updateCounts_[1] += proximitySources(loops, bm, cs, rules, &sources);
  std::vector<ShortSegment> shortSegments;

  const double tol = o_.metric.chordTolerance;
  for (const auto& contourSlots : ps_[size_t(p)].slots)
    for (int si : contourSlots) {
      Slot& s = slots_[size_t(si)];
      const Slot* other = s.master >= 0     ? &slots_[size_t(s.master)]
                          : s.follower >= 0 ? &slots_[size_t(s.follower)]
                                            : nullptr;
      const bool reversed = other && (s.master >= 0 ? s.masterReversed : slots_[size_t(s.follower)].masterReversed);
      const int owner = s.master >= 0 ? s.master : si;  // the slot that gets re-discretized
      const size_t n = s.t.size();
      for (size_t i = 0; i + 1 < n; ++i) {
        const Vec2 u0 = uvOf(s, i), u1 = uvOf(s, i + 1);
        const double l = segmentMetricLength(cs, u0, u1);
        double lOther = 0.0;
        if (other) {
          const size_t j = reversed ? n - 1 - i : i, j1 = reversed ? j - 1 : j + 1;
          lOther = segmentMetricLength(space(other->patch), uvOf(*other, j), uvOf(*other, j1));
        }
        // (b) Contour chord: the 3D chord against the 3D contour at the segment's middle
        // parameter; the size along it from the sagitta (deviation ~ h^2), across it dMax times that.
        const Vec3 x0 = surf.point(u0), x1 = surf.point(u1);
        const Vec3 xm = surf.point(s.c->point(0.5 * (s.t[i] + s.t[i + 1])));
        const double dev = (xm - 0.5 * (x0 + x1)).norm();
        if (tol > 0 && dev > tol) {
          const Vec2 d = u1 - u0;
          const double h = 0.9 * d.norm() * std::sqrt(tol / dev);
          sources.emplace_back(
              std::in_place_type<SegmentSource>,
              SegmentSource{u0, u1, Metric::fromSizes(pm::atan2(d.y(), d.x()), h, rules.dMax * h), 0.5 * d.norm()});
          slots_[size_t(owner)].invalid = true;
          ++updateCounts_[0];
        }
        // (a) eps1, unless without adaptation the shortness only comes from the neighbour's
        // stricter metric; a shared segment is judged by the longer of its two lengths.
        const bool neighbourMadeIt = other && lOther > l;
        if (l < rules.eps1 && (o_.adaptation || !neighbourMadeIt)) shortSegments.push_back({u0, u1, l, s.contour});
        const double lEff = std::max(l, lOther);
        const bool canCoarsen = n > 2 && n - 1 > size_t(s.minSegments);
        if ((lEff < rules.lengthMin && canCoarsen) || lEff > rules.lengthMax) slots_[size_t(owner)].invalid = true;
      }
    }
  updateCounts_[2] += shortSegmentSources(shortSegments, cs, 0.0, &sources);
  for (auto& src : sources) pending_[size_t(p)].push_back(std::move(src));
}

}  // namespace surface_mesher
}  // namespace anisomesh

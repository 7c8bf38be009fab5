// Surface meshing: the 3D measures of a run's merged mesh (SurfaceMeshReport::quality, the
// per-element quality and per-edge length), in each patch's control space pulled forward
// into 3D. Made at the end of the run, or later (SurfaceMeshOptions::deferQuality) in two
// parts: the per-element values (the colouring; every control-space query) and the chord
// deviations (surface evaluations only), with the same results in both cases.
#include <unordered_set>

#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

void DeferredMeasures::measureElements() {
  if (elementsDone) return;
  const auto t0 = Clock::now();
  q = Surface3DQuality();
  q.edgeLengthMin = q.qualityMin = std::numeric_limits<double>::infinity();
  double lenSum = 0.0, qSum = 0.0;
  int count = 0, within = 0;
  std::vector<double> quadQuality;
  std::unordered_set<std::uint64_t> seen;  // distinct edges (merged-mesh vertex pairs)
  size_t elements = 0;
  for (const MeasuredPatch& mp : patches) elements += mp.triangles.size() + mp.quads.size();
  seen.reserve(2 * elements);
  edgeLengths.clear();
  edgeAt.clear();
  elementQuality.clear();
  for (size_t p = 0; p < patches.size(); ++p) {
    const MeasuredPatch& mp = patches[p];
    const Surface& surf = *mp.surface;
    const ControlSpace& cs = *mp.space;
    auto metric3 = [&](const Vec2& uv) {  // (needs Su, Sv only)
      const SurfaceDerivatives d = surf.firstDerivatives(uv);
      return metric3DFromParameter(cs.metricAt(uv), d);
    };
    // The metric at each point, made once for all its edges (the same value each time).
    std::vector<Mat3> atPoint(mp.params.size());
    std::vector<char> known(mp.params.size(), 0);
    auto pointMetric = [&](int i) -> const Mat3& {
      if (!known[size_t(i)]) {
        atPoint[size_t(i)] = metric3(mp.params[size_t(i)]);
        known[size_t(i)] = 1;
      }
      return atPoint[size_t(i)];
    };
    // Once per merged edge, in the patch that meets it first.
    auto measureEdge = [&](int i0, int i1) {
      const int g0 = mp.gid[size_t(i0)], g1 = mp.gid[size_t(i1)];
      const int a = std::min(g0, g1), b = std::max(g0, g1);
      if (!seen.insert(std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b)).second) return;
      const Vec2 u0 = mp.params[size_t(i0)], u1 = mp.params[size_t(i1)];
      const Vec3& x0 = points[size_t(g0)];
      const Vec3& x1 = points[size_t(g1)];
      const double l0 = edgeLength3D(x0, x1, pointMetric(i0));
      const double l =
          (l0 + 4.0 * edgeLength3D(x0, x1, metric3(0.5 * (u0 + u1))) + edgeLength3D(x0, x1, pointMetric(i1))) / 6.0;
      lenSum += l;
      edgeLengths.push_back({a, b, l});
      edgeAt.push_back({int(p), i0, i1});
      q.edgeLengthMin = std::min(q.edgeLengthMin, l);
      q.edgeLengthMax = std::max(q.edgeLengthMax, l);
      if (l >= std::sqrt(0.5) && l <= std::sqrt(2.0)) ++within;
      ++q.edges;
    };
    for (const auto& t : mp.triangles) {
      const Vec2 a = mp.params[size_t(t[0])], b = mp.params[size_t(t[1])], c = mp.params[size_t(t[2])];
      const double qq = triangleQuality3D(points[size_t(mp.gid[size_t(t[0])])], points[size_t(mp.gid[size_t(t[1])])],
                                          points[size_t(mp.gid[size_t(t[2])])], metric3((a + b + c) / 3.0));
      qSum += qq;
      elementQuality.push_back(qq);
      q.qualityMin = std::min(q.qualityMin, qq);
      ++count;
      for (int k = 0; k < 3; ++k) measureEdge(t[size_t(k)], t[size_t((k + 1) % 3)]);
    }
    for (const auto& t : mp.quads) {
      Vec2 tu[4];
      Vec3 tx[4];
      for (int k = 0; k < 4; ++k)
        tu[k] = mp.params[size_t(t[size_t(k)])], tx[k] = points[size_t(mp.gid[size_t(t[size_t(k)])])];
      const double qq = quadQuality3D(tx, metric3(0.25 * (tu[0] + tu[1] + tu[2] + tu[3])));
      qSum += qq;
      quadQuality.push_back(qq);
      q.qualityMin = std::min(q.qualityMin, qq);
      ++count;
      for (int k = 0; k < 4; ++k) measureEdge(t[size_t(k)], t[size_t((k + 1) % 4)]);
    }
  }
  elementQuality.insert(elementQuality.end(), quadQuality.begin(), quadQuality.end());
  q.edgesWithinSqrt2 = q.edges ? double(within) / q.edges : 0.0;
  q.edgeLengthMean = q.edges ? lenSum / q.edges : 0.0;
  q.qualityMean = count ? qSum / count : 0.0;
  if (!q.edges) q.edgeLengthMin = 0.0;
  if (!count) q.qualityMin = 0.0;
  elementsDone = true;
  seconds += secondsSince(t0);
}

void DeferredMeasures::measureChords() {
  if (chordsDone) return;
  measureElements();
  const auto t0 = Clock::now();
  for (const MeasuredPatch& mp : patches) {
    const Surface& surf = *mp.surface;
    for (const auto& t : mp.triangles) {
      const Vec2 tu[3] = {mp.params[size_t(t[0])], mp.params[size_t(t[1])], mp.params[size_t(t[2])]};
      const Vec2 &a = tu[0], &b = tu[1], &c = tu[2];
      const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (!(area > 0)) ++q.inverted;
      const Vec3 tx[3] = {points[size_t(mp.gid[size_t(t[0])])], points[size_t(mp.gid[size_t(t[1])])],
                          points[size_t(mp.gid[size_t(t[2])])]};
      q.chordDeviationMax = std::max(q.chordDeviationMax, normalTriangleDeviation(surf, tu, tx));
    }
    for (const auto& t : mp.quads) {
      Vec2 tu[4];
      Vec3 tx[4];
      for (int k = 0; k < 4; ++k)
        tu[k] = mp.params[size_t(t[size_t(k)])], tx[k] = points[size_t(mp.gid[size_t(t[size_t(k)])])];
      // Inverted: a corner turning clockwise in (u, v) (non-convex or clockwise quad).
      bool convex = true;
      for (int k = 0; k < 4; ++k) {
        const Vec2 e1 = tu[(k + 1) % 4] - tu[k], e0 = tu[k] - tu[(k + 3) % 4];
        convex = convex && e0.x() * e1.y() - e0.y() * e1.x() > 0;
      }
      if (!convex) ++q.inverted;
      // Chord deviation over the two triangles (0, 1, 2), (0, 2, 3) of the flat-split quad.
      for (int d = 0; d < 2; ++d) {
        const Vec2 su[3] = {tu[0], tu[1 + d], tu[2 + d]};
        const Vec3 sx[3] = {tx[0], tx[1 + d], tx[2 + d]};
        q.chordDeviationMax = std::max(q.chordDeviationMax, normalTriangleDeviation(surf, su, sx));
      }
    }
  }
  // Edges: in the patch whose element met them first (as their lengths); both gaps from
  // one set of surface evaluations.
  for (const auto& e : edgeAt) {
    const MeasuredPatch& mp = patches[size_t(e[0])];
    const Surface& surf = *mp.surface;
    const Vec2 u0 = mp.params[size_t(e[1])], u1 = mp.params[size_t(e[2])];
    const Vec3& x0 = points[size_t(mp.gid[size_t(e[1])])];
    const Vec3& x1 = points[size_t(mp.gid[size_t(e[2])])];
    const EdgeChordGaps g = edgeChordGaps(surf, u0, u1, x0, x1);
    q.isoChordDeviationMax = std::max(q.isoChordDeviationMax, g.iso);
    q.edgeChordDeviationMax = std::max(q.edgeChordDeviationMax, g.normal);
  }
  q.chordDeviationMax = std::max(q.chordDeviationMax, q.edgeChordDeviationMax);
  q.chordDeviationMaxRelative = chordTolerance > 0 ? q.chordDeviationMax / chordTolerance : 0.0;
  chordsDone = true;
  seconds += secondsSince(t0);
}

void DeferredMeasures::fill(SurfaceMeshReport& report) const {
  report.elementQuality = elementQuality;
  report.edgeLengths = edgeLengths;
  if (chordsDone) report.quality = q;
  report.controlSpaceQueries = counters->queries();
  report.controlSpaceSeconds = counters->querySeconds();
}

}  // namespace surface_mesher

void measureSurfaceElements(SurfaceMeshReport& report) {
  if (!report.deferred) return;
  report.deferred->measureElements();
  report.deferred->fill(report);
}

void finishSurfaceMeasures(SurfaceMeshReport& report) {
  if (!report.deferred) return;
  report.deferred->measureChords();
  report.deferred->fill(report);
  report.secondsTotal += report.deferred->seconds;  // (the run's total, measures included)
  report.deferred.reset();
}

}  // namespace anisomesh

// Surface meshing: the 3D measures of a run's merged mesh (SurfaceMeshReport::quality, the
// per-element quality and per-edge length), in each patch's control space pulled forward
// into 3D. Made at the end of the run, or later (SurfaceMeshOptions::deferQuality) in two
// parts: the per-element values (the colouring; every control-space query) and the chord
// deviations (surface evaluations only), with the same results in both cases.
#include <functional>
#include <unordered_set>

#include "anisomesh/controlspace/concurrency.h"
#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

namespace {

// parallelChunks when concurrent, else the same chunks in order on this thread.
void forChunks(bool concurrent, size_t n, size_t grain, const std::function<void(size_t, size_t, size_t)>& f) {
  if (concurrent) {
    parallelChunks(n, grain, f);
    return;
  }
  for (size_t c = 0; c < chunkCount(n, grain); ++c) f(c, c * grain, std::min(n, (c + 1) * grain));
}

constexpr size_t kMeasureGrain = 1024;

// Quad t's corners: (u, v) and 3D points.
void quadCorners(const MeasuredPatch& mp, const std::vector<Vec3>& points, const std::array<int, 4>& t, Vec2 tu[4],
                 Vec3 tx[4]) {
  for (int j = 0; j < 4; ++j)
    tu[j] = mp.params[size_t(t[size_t(j)])], tx[j] = points[size_t(mp.gid[size_t(t[size_t(j)])])];
}

}  // namespace

// In three passes, so the control-space queries (the costly part) run in parallel chunks
// when the patch's space allows: the distinct edges in the order the elements meet them
// (which patch measures each), the values (metric per needed point, element qualities,
// edge lengths), then the sums and extremes in the order of the one-pass form: the same
// bits and the same queries for any thread count.
void DeferredMeasures::measureElements() {
  if (elementsDone) return;
  const auto t0 = Clock::now();
  q = Surface3DQuality();
  q.edgeLengthMin = q.qualityMin = std::numeric_limits<double>::infinity();
  std::unordered_set<std::uint64_t> seen;  // distinct edges (merged-mesh vertex pairs)
  size_t elements = 0, triangles = 0;
  for (const MeasuredPatch& mp : patches) {
    triangles += mp.triangles.size();
    elements += mp.triangles.size() + mp.quads.size();
  }
  seen.reserve(2 * elements);
  edgeLengths.clear();
  edgeAt.clear();
  elementQuality.assign(elements, 0.0);  // triangles (all patches), then quads
  std::vector<size_t> edgesOf(patches.size() + 1, 0), trianglesOf(patches.size() + 1, 0),
      quadsOf(patches.size() + 1, triangles);
  std::vector<std::vector<char>> needed(patches.size());
  for (size_t p = 0; p < patches.size(); ++p) {
    const MeasuredPatch& mp = patches[p];
    std::vector<char>& need = needed[p];
    need.assign(mp.params.size(), 0);
    // Once per merged edge, in the patch that meets it first.
    auto meet = [&](int i0, int i1) {
      const int g0 = mp.gid[size_t(i0)], g1 = mp.gid[size_t(i1)];
      const int a = std::min(g0, g1), b = std::max(g0, g1);
      if (!seen.insert(std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b)).second) return;
      edgeAt.push_back({int(p), i0, i1});
      edgeLengths.push_back({a, b, 0.0});
      need[size_t(i0)] = need[size_t(i1)] = 1;
    };
    for (const auto& t : mp.triangles)
      for (int k = 0; k < 3; ++k) meet(t[size_t(k)], t[size_t((k + 1) % 3)]);
    for (const auto& t : mp.quads)
      for (int k = 0; k < 4; ++k) meet(t[size_t(k)], t[size_t((k + 1) % 4)]);
    edgesOf[p + 1] = edgeAt.size();
    trianglesOf[p + 1] = trianglesOf[p] + mp.triangles.size();
    quadsOf[p + 1] = quadsOf[p] + mp.quads.size();
  }
  for (size_t p = 0; p < patches.size(); ++p) {
    const MeasuredPatch& mp = patches[p];
    const Surface& surf = *mp.surface;
    const ControlSpace& cs = *mp.space;
    const bool concurrent = queriesAreConcurrent(cs);
    auto metric3 = [&](const Vec2& uv) {  // (needs Su, Sv only)
      const SurfaceDerivatives d = surf.firstDerivatives(uv);
      return metric3DFromParameter(cs.metricAt(uv), d);
    };
    // The metric at each point an edge reads, made once for all its edges.
    std::vector<Mat3> atPoint(mp.params.size());
    forChunks(concurrent, mp.params.size(), kMeasureGrain, [&](size_t, size_t b, size_t e) {
      for (size_t i = b; i < e; ++i)
        if (needed[p][i]) atPoint[i] = metric3(mp.params[i]);
    });
    forChunks(concurrent, mp.triangles.size(), kMeasureGrain, [&](size_t, size_t b, size_t e) {
      for (size_t k = b; k < e; ++k) {
        const auto& t = mp.triangles[k];
        const Vec2 a = mp.params[size_t(t[0])], bb = mp.params[size_t(t[1])], c = mp.params[size_t(t[2])];
        elementQuality[trianglesOf[p] + k] =
            triangleQuality3D(points[size_t(mp.gid[size_t(t[0])])], points[size_t(mp.gid[size_t(t[1])])],
                              points[size_t(mp.gid[size_t(t[2])])], metric3((a + bb + c) / 3.0));
      }
    });
    forChunks(concurrent, mp.quads.size(), kMeasureGrain, [&](size_t, size_t b, size_t e) {
      for (size_t k = b; k < e; ++k) {
        Vec2 tu[4];
        Vec3 tx[4];
        quadCorners(mp, points, mp.quads[k], tu, tx);
        elementQuality[quadsOf[p] + k] = quadQuality3D(tx, metric3(0.25 * (tu[0] + tu[1] + tu[2] + tu[3])));
      }
    });
    forChunks(concurrent, edgesOf[p + 1] - edgesOf[p], kMeasureGrain, [&](size_t, size_t b, size_t e) {
      for (size_t k = edgesOf[p] + b; k < edgesOf[p] + e; ++k) {
        const int i0 = edgeAt[k][1], i1 = edgeAt[k][2];
        const Vec2 u0 = mp.params[size_t(i0)], u1 = mp.params[size_t(i1)];
        const Vec3& x0 = points[size_t(mp.gid[size_t(i0)])];
        const Vec3& x1 = points[size_t(mp.gid[size_t(i1)])];
        const double l0 = edgeLength3D(x0, x1, atPoint[size_t(i0)]);
        edgeLengths[k].length =
            (l0 + 4.0 * edgeLength3D(x0, x1, metric3(0.5 * (u0 + u1))) + edgeLength3D(x0, x1, atPoint[size_t(i1)])) /
            6.0;
      }
    });
  }
  // Sums in the one-pass order: per patch its triangles, then its quads; edges as met.
  double lenSum = 0.0, qSum = 0.0;
  int within = 0;
  for (size_t p = 0; p < patches.size(); ++p) {
    for (size_t k = trianglesOf[p]; k < trianglesOf[p + 1]; ++k) qSum += elementQuality[k];
    for (size_t k = quadsOf[p]; k < quadsOf[p + 1]; ++k) qSum += elementQuality[k];
  }
  for (const double qq : elementQuality) q.qualityMin = std::min(q.qualityMin, qq);
  for (const SurfaceEdgeLength& e : edgeLengths) {
    const double l = e.length;
    lenSum += l;
    q.edgeLengthMin = std::min(q.edgeLengthMin, l);
    q.edgeLengthMax = std::max(q.edgeLengthMax, l);
    if (l >= std::sqrt(0.5) && l <= std::sqrt(2.0)) ++within;
  }
  const int count = int(elements);
  q.edges = int(edgeLengths.size());
  q.edgesWithinSqrt2 = q.edges ? double(within) / q.edges : 0.0;
  q.edgeLengthMean = q.edges ? lenSum / q.edges : 0.0;
  q.qualityMean = count ? qSum / count : 0.0;
  if (!q.edges) q.edgeLengthMin = 0.0;
  if (!count) q.qualityMin = 0.0;
  elementsDone = true;
  seconds += secondsSince(t0);
}

// The largest deviations in parallel chunks (a maximum is the same in any order; NaN never
// wins, as in one pass) and the inverted elements counted per chunk.
void DeferredMeasures::measureChords() {
  if (chordsDone) return;
  measureElements();
  const auto t0 = Clock::now();
  struct Part {
    double chord = 0.0, iso = 0.0, edge = 0.0;
    int inverted = 0;
  };
  auto gather = [&](std::vector<Part>& parts) {
    for (const Part& r : parts) {
      q.chordDeviationMax = std::max(q.chordDeviationMax, r.chord);
      q.isoChordDeviationMax = std::max(q.isoChordDeviationMax, r.iso);
      q.edgeChordDeviationMax = std::max(q.edgeChordDeviationMax, r.edge);
      q.inverted += r.inverted;
    }
  };
  for (const MeasuredPatch& mp : patches) {
    const Surface& surf = *mp.surface;
    std::vector<Part> parts(chunkCount(mp.triangles.size(), kMeasureGrain));
    parallelChunks(mp.triangles.size(), kMeasureGrain, [&](size_t c, size_t b, size_t e) {
      Part& r = parts[c];
      for (size_t k = b; k < e; ++k) {
        const auto& t = mp.triangles[k];
        const Vec2 tu[3] = {mp.params[size_t(t[0])], mp.params[size_t(t[1])], mp.params[size_t(t[2])]};
        const Vec2 &a = tu[0], &bb = tu[1], &cc = tu[2];
        const double area = (bb - a).x() * (cc - a).y() - (bb - a).y() * (cc - a).x();
        if (!(area > 0)) ++r.inverted;
        const Vec3 tx[3] = {points[size_t(mp.gid[size_t(t[0])])], points[size_t(mp.gid[size_t(t[1])])],
                            points[size_t(mp.gid[size_t(t[2])])]};
        r.chord = std::max(r.chord, normalTriangleDeviation(surf, tu, tx));
      }
    });
    gather(parts);
    parts.assign(chunkCount(mp.quads.size(), kMeasureGrain), Part());
    parallelChunks(mp.quads.size(), kMeasureGrain, [&](size_t c, size_t b, size_t e) {
      Part& r = parts[c];
      for (size_t k = b; k < e; ++k) {
        Vec2 tu[4];
        Vec3 tx[4];
        quadCorners(mp, points, mp.quads[k], tu, tx);
        // Inverted: a corner turning clockwise in (u, v) (non-convex or clockwise quad).
        bool convex = true;
        for (int j = 0; j < 4; ++j) {
          const Vec2 e1 = tu[(j + 1) % 4] - tu[j], e0 = tu[j] - tu[(j + 3) % 4];
          convex = convex && e0.x() * e1.y() - e0.y() * e1.x() > 0;
        }
        if (!convex) ++r.inverted;
        // Chord deviation over the two triangles (0, 1, 2), (0, 2, 3) of the flat-split quad.
        for (int d = 0; d < 2; ++d) {
          const Vec2 su[3] = {tu[0], tu[1 + d], tu[2 + d]};
          const Vec3 sx[3] = {tx[0], tx[1 + d], tx[2 + d]};
          r.chord = std::max(r.chord, normalTriangleDeviation(surf, su, sx));
        }
      }
    });
    gather(parts);
  }
  // Edges: in the patch whose element met them first (as their lengths); both gaps from
  // one set of surface evaluations.
  std::vector<Part> parts(chunkCount(edgeAt.size(), kMeasureGrain));
  parallelChunks(edgeAt.size(), kMeasureGrain, [&](size_t c, size_t b, size_t e) {
    Part& r = parts[c];
    for (size_t k = b; k < e; ++k) {
      const auto& at = edgeAt[k];
      const MeasuredPatch& mp = patches[size_t(at[0])];
      const Vec2 u0 = mp.params[size_t(at[1])], u1 = mp.params[size_t(at[2])];
      const Vec3& x0 = points[size_t(mp.gid[size_t(at[1])])];
      const Vec3& x1 = points[size_t(mp.gid[size_t(at[2])])];
      const EdgeChordGaps g = edgeChordGaps(*mp.surface, u0, u1, x0, x1);
      r.iso = std::max(r.iso, g.iso);
      r.edge = std::max(r.edge, g.normal);
    }
  });
  gather(parts);
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

// Planar domain decomposition: the parts meshed (in parallel) and merged into one mesh
// (see mesh/domain_decomposition.h).
#include <algorithm>
#include <sstream>
#include <vector>

#include "anisomesh/controlspace/concurrency.h"
#include "anisomesh/core/caller_progress.h"
#include "anisomesh/core/clock.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/mesh/domain_decomposition.h"
#include "mesh_internal.h"

namespace anisomesh {

Mesh meshDomainParts(const std::vector<BoundaryLoop>& loops, const DomainParts& parts, const ControlSpace& cs,
                     const PlanarMesherOptions& options) {
  const size_t n = parts.parts.size();
  std::vector<Mesh> meshes(n);
  std::vector<MesherTimings> timings(n);
  // Progress: each part stores its fraction; only the calling thread reports the mean (the
  // whole domain's boundary stage reported 0.1 before the parts started). A false answer
  // stops every part at its next tick (ErrorCode::Cancelled).
  CallerProgress progress(n, options.progress, 0.1, 0.9);
  // Larger parts first (by boundary size, a stand-in for their work): better balance.
  std::vector<size_t> order(n);
  for (size_t p = 0; p < n; ++p) order[p] = p;
  auto loopPoints = [&](size_t p) {
    size_t s = 0;
    for (const auto& l : parts.parts[p].loops) s += l.size();
    return s;
  };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return loopPoints(a) > loopPoints(b); });
  // The parts' options, copied here without the caller's callback: a part thread copies
  // them, and copying the callback could copy what only its thread may touch (a JS function).
  PlanarMesherOptions partOptions = options;
  partOptions.progress = nullptr;
  partOptions.partElements = 0;
  auto meshPart = [&](size_t p) {
    const DomainPart& part = parts.parts[p];
    std::vector<BoundaryLoop> partLoops(part.loops.size());
    for (size_t l = 0; l < part.loops.size(); ++l) {
      for (int id : part.loops[l]) partLoops[l].points.push_back(parts.points[id]);
      partLoops[l].edgeRefs = part.edgeRefs[l];
    }
    PlanarMesherOptions o = partOptions;
    o.timings = &timings[p];
    o.boundaryCache = nullptr;  // the parts run concurrently, on loops of their own
    if (options.progress) o.progress = progress.task(p);
    meshes[p] = meshPlanarBoundary(partLoops, cs, o);
  };
  if (queriesAreConcurrent(cs)) {
    parallelChunks(
        n, 1, [&](size_t c, size_t, size_t) { meshPart(order[c]); },
        options.progress ? progress.poll() : std::function<void()>());
  } else {
    for (size_t c = 0; c < n; ++c) meshPart(order[c]);
  }

  // Merge: the loops' and chords' points keep their global ids, inner points follow part by part.
  Mesh m;
  m.dimension = 2;
  size_t total = parts.points.size();
  std::vector<size_t> innerBase(n);
  for (size_t p = 0; p < n; ++p) {
    size_t nb = 0;
    for (const auto& l : parts.parts[p].loops) nb += l.size();
    innerBase[p] = total;
    total += meshes[p].points.size() - nb;
  }
  m.points.resize(total);
  m.params.resize(total);
  m.pointRefs.assign(total, 0);
  // Each part's triangles and quads at offsets known beforehand: the parts write their own
  // ranges concurrently (the same arrays as appending them part by part).
  std::vector<size_t> triBase(n + 1, 0), triRefBase(n + 1, 0), quadBase(n + 1, 0), quadRefBase(n + 1, 0);
  for (size_t p = 0; p < n; ++p) {
    triBase[p + 1] = triBase[p] + meshes[p].triangles.size();
    triRefBase[p + 1] = triRefBase[p] + meshes[p].triangleRefs.size();
    quadBase[p + 1] = quadBase[p] + meshes[p].quads.size();
    quadRefBase[p + 1] = quadRefBase[p] + meshes[p].quadRefs.size();
  }
  m.triangles.resize(triBase[n]);
  m.triangleRefs.resize(triRefBase[n]);
  m.quads.resize(quadBase[n]);
  m.quadRefs.resize(quadRefBase[n]);
  // Chunks: the loops' and chords' points first, then one per part.
  const size_t shared = parts.points.size();
  parallelChunks(n + 1, 1, [&](size_t c, size_t, size_t) {
    if (c == 0) {
      for (size_t i = 0; i < shared; ++i) {
        m.params[i] = parts.points[i];
        m.points[i] = Vec3(parts.points[i].x(), parts.points[i].y(), 0.0);
      }
      return;
    }
    const size_t p = c - 1;
    Mesh pm = std::move(meshes[p]);  // released here, on the thread that merged it
    std::vector<int> map;
    for (const auto& l : parts.parts[p].loops) map.insert(map.end(), l.begin(), l.end());
    const size_t nb = map.size();
    map.reserve(pm.points.size());
    for (size_t v = nb; v < pm.points.size(); ++v) {
      const size_t g = innerBase[p] + (v - nb);
      map.push_back(static_cast<int>(g));
      m.points[g] = pm.points[v];
      m.params[g] = pm.points[v].head<2>();
    }
    for (size_t k = 0; k < pm.triangles.size(); ++k) {
      const auto& t = pm.triangles[k];
      m.triangles[triBase[p] + k] = {map[t[0]], map[t[1]], map[t[2]]};
    }
    std::copy(pm.triangleRefs.begin(), pm.triangleRefs.end(), m.triangleRefs.begin() + triRefBase[p]);
    for (size_t k = 0; k < pm.quads.size(); ++k) {
      const auto& q = pm.quads[k];
      m.quads[quadBase[p] + k] = {map[q[0]], map[q[1]], map[q[2]], map[q[3]]};
    }
    std::copy(pm.quadRefs.begin(), pm.quadRefs.end(), m.quadRefs.begin() + quadRefBase[p]);
  });
  MesherTimings sum;
  for (size_t p = 0; p < n; ++p) {
    sum.boundary += timings[p].boundary;
    sum.insertion += timings[p].insertion;
    sum.improvement += timings[p].improvement;
    sum.quads += timings[p].quads;
    sum.estimatedElements += timings[p].estimatedElements;
  }
  // Boundary edges: the input loops' edges in input order, as the single-part mesher gives them.
  // The loops' points come first, then the cuts' points (polished now that both sides are known).
  int base = 0;
  for (const BoundaryLoop& l : loops) {
    const int k = static_cast<int>(l.points.size());
    for (int i = 0; i < k; ++i) {
      m.edges.push_back({base + i, base + (i + 1) % k});
      m.edgeRefs.push_back(l.edgeRefs[i]);
    }
    base += k;
  }
  {
    const auto t0 = Clock::now();
    polishDecompositionSeams(m, base, static_cast<int>(parts.points.size()), cs, options);
    sum.improvement += secondsSince(t0);
  }
  if (m.elementCount() > options.maxElements) {
    std::ostringstream os;
    os << "meshPlanarBoundary: the mesh has " << m.elementCount() << " elements, above the element budget of "
       << options.maxElements;
    throw Error(ErrorCode::ElementBudgetExceeded, os.str());
  }
  sum.parts = static_cast<int>(n);
  if (options.timings) *options.timings = sum;
  return m;
}

}  // namespace anisomesh

// Surface meshing, paper section 3 (Algorithm 1): per-patch control spaces in the
// parameter plane, shared contours discretized once in 3D, the invalidation loop
// (segment length, contour chord, boundary proximity), adaptation of neighbouring
// control spaces across shared contours, inner meshing and merging.
#include "anisomesh/surface/surface_mesh.h"

#include "anisomesh/controlspace/concurrency.h"
#include "anisomesh/core/caller_progress.h"
#include "anisomesh/mesh/all_quad_split.h"
#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

// Patch checks: domain valid, contours inside the surface's parameter box, no NaN and no
// degenerate parameterization on contours or at most of a grid of interior points.
void checkPatch(const SurfacePatch& p, int index) {
  const std::string label = patchLabel(p, index);
  require(p.surface != nullptr, ErrorCode::InvalidArgument, label + ": no surface");
  try {
    validateDomain(p.domain);
  } catch (const Error& e) {
    throw Error(e.code(), label + ": " + e.what());
  }
  const Box2 box = p.surface->domain();
  const double tol = 1e-9 * (1.0 + box.size().norm());
  auto derivs = [&](const Vec2& uv) {
    try {
      return p.surface->derivatives(uv);
    } catch (const Error& e) {
      throw Error(e.code(), label + ": " + e.what());
    }
  };
  for (int k = 0; k < contourCount(p); ++k)
    for (const Vec2& q : sampleContour(contourOf(p, k), 16)) {
      require(q.x() >= box.lo.x() - tol && q.x() <= box.hi.x() + tol && q.y() >= box.lo.y() - tol &&
                  q.y() <= box.hi.y() + tol,
              ErrorCode::InvalidDomain,
              label + ": " + contourName(k) + " leaves the surface's parameter domain [" + fmt(box.lo.x()) + ", " +
                  fmt(box.hi.x()) + "] x [" + fmt(box.lo.y()) + ", " + fmt(box.hi.y()) + "] at " + fmtUv(q));
      if (isDegenerate(derivs(q)))
        throw Error(ErrorCode::InvalidSurface,
                    label + ": degenerate parameterization (Su x Sv = 0) on " + contourName(k) + " at " + fmtUv(q));
    }
  const auto outer = sampleContour(p.domain.outer, 16);
  std::vector<std::vector<Vec2>> holes;
  for (const auto& h : p.domain.holes) holes.push_back(sampleContour(h, 16));
  int inside = 0, degenerate = 0;
  Vec2 firstBad;
  constexpr int kGrid = 12;
  auto sample = [&](int i, int j) {
    return Vec2(box.lo + Vec2(box.size().x() * (i + 0.5) / kGrid, box.size().y() * (j + 0.5) / kGrid));
  };
  auto cell = [](int i, int j) { return static_cast<size_t>(i) * kGrid + static_cast<size_t>(j); };
  std::vector<char> in(kGrid * kGrid, 0);
  std::vector<Vec3> normals(kGrid * kGrid);  // Su x Sv of the non-degenerate inside samples
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec2 q = sample(i, j);
      if (!pointInPolygon(outer, q)) continue;
      bool inHole = false;
      for (const auto& h : holes) inHole = inHole || pointInPolygon(h, q);
      if (inHole) continue;
      ++inside;
      const SurfaceDerivatives d = derivs(q);
      if (isDegenerate(d)) {
        if (degenerate++ == 0) firstBad = q;
      } else {
        in[cell(i, j)] = 1;
        normals[cell(i, j)] = d.su.cross(d.sv);
      }
    }
  if (degenerate > 0 && 10 * degenerate > inside)
    throw Error(ErrorCode::InvalidSurface, label + ": degenerate parameterization (Su x Sv = 0) at " + fmtUv(firstBad) +
                                               " and " + std::to_string(degenerate - 1) + " more sample points");
  // A fold: between two neighbouring samples the normal turns over and Su x Sv vanishes on
  // the way (x = u^2 over [-1, 1] covers x in [0, 1] twice). Bisection finds where the
  // normal turns; a kink (|u|) or a tight bend turns it with Su x Sv far from 0 and passes.
  auto normal = [&](const Vec2& q, double* area) {
    const SurfaceDerivatives d = derivs(q);
    const Vec3 n = d.su.cross(d.sv);
    *area = n.norm();
    return Vec3(n / (*area > 0.0 ? *area : 1.0));
  };
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j)
      for (const auto& [di, dj] : {std::make_pair(1, 0), std::make_pair(0, 1)}) {
        if (i + di >= kGrid || j + dj >= kGrid || !in[cell(i, j)] || !in[cell(i + di, j + dj)]) continue;
        const Vec3 &ca = normals[cell(i, j)], &cb = normals[cell(i + di, j + dj)];
        if (!(ca.dot(cb) < 0.0)) continue;  // the usual case: no evaluation beyond the grid's
        Vec2 a = sample(i, j), b = sample(i + di, j + dj);
        const double areaA = ca.norm(), areaB = cb.norm();
        double area;
        const Vec3 na = ca / areaA;
        Vec2 m = 0.5 * (a + b);
        for (int k = 0; k < 60; ++k) {
          m = 0.5 * (a + b);
          const Vec3 nm = normal(m, &area);
          if (!(area > 0.0)) break;
          (nm.dot(na) > 0.0 ? a : b) = m;
        }
        normal(m, &area);
        if (!(area > 1e-6 * std::max(areaA, areaB)))
          throw Error(ErrorCode::InvalidSurface, label +
                                                     ": the surface folds over itself (Su x Sv = 0 and the normal "
                                                     "turns over) near " +
                                                     fmtUv(m));
      }
}

Mesh ModelMesher::run(SurfaceMeshReport* report) {
  const auto t0 = Clock::now();
  require(!m_.patches.empty(), ErrorCode::InvalidArgument, "surface model: no patch");
  validate(o_.metric);
  for (size_t p = 0; p < m_.patches.size(); ++p) checkPatch(m_.patches[p], int(p));
  size_ = modelSize(m_);
  setupSlots();
  validateSharing();
  assignCornerIds();

  report_ = report;
  BoundaryUpdateOptions rules = o_.boundary;
  rules.maxRounds = std::max(1, o_.maxRounds);
  Algorithm1Report rounds;
  Mesh out = runAlgorithm1(*this, rules, &rounds);
  if (report) {
    report->rounds = rounds.rounds;
    report->converged = rounds.converged;
    report->chordSources = updateCounts_[0];
    report->proximitySources = updateCounts_[1];
    report->shortSegmentSources = updateCounts_[2];
    report->invalidations = invalidations_;
    report->secondsTotal = secondsSince(t0);
  }
  return out;
}

// 1-2: initial control spaces, every contour invalid.
void ModelMesher::buildControlSpaces() {
  for (size_t p = 0; p < m_.patches.size(); ++p) {
    try {
      const std::vector<Vec2> shifts = seamShifts(m_, int(p));
      if (shifts.empty() || m_.patches[p].sources.empty()) {
        ps_[p].cs = buildControlSpaceImpl(m_.patches[p], m_.sources3d, o_, *counters_, &ps_[p].stageKey);
      } else {
        SurfacePatch periodic = m_.patches[p];
        periodic.sources = withSeamImages(periodic.sources, shifts);
        ps_[p].cs = buildControlSpaceImpl(periodic, m_.sources3d, o_, *counters_, &ps_[p].stageKey);
      }
    } catch (const Error& e) {
      throw Error(e.code(), patchLabel(m_.patches[p], int(p)) + ": " + e.what());
    }
    refreshQueries(p);
  }
}

void ModelMesher::refreshQueries(size_t p) {
  PatchState& st = ps_[p];
  const ControlSpace* inner = st.cs.get();
  st.parameterized.reset();
  if (o_.parameterization != ParameterizationStorage::Folded) {
    const std::shared_ptr<const Surface> surf = m_.patches[p].surface;
    const Box2 dom = surf->domain();
    st.parameterized = std::make_unique<ParameterizedControlSpace>(
        *st.cs,
        [surf, dom](const Vec2& uv) { return parameterizationMatrix(*surf, uv.cwiseMax(dom.lo).cwiseMin(dom.hi)); },
        o_.parameterization);
    inner = st.parameterized.get();
  }
  st.counted =
      std::make_unique<CountingControlSpace>(*inner, *m_.patches[p].surface, *counters_, st.parameterized != nullptr);
}

// 4: the invalid contours discretized (shared ones once, for both patches); after the
// first round the control spaces of patches across shared contours are adapted.
void ModelMesher::discretizeInvalidContours(int round) {
  for (size_t s = 0; s < slots_.size(); ++s)
    if (slots_[s].invalid && slots_[s].master < 0) {
      ps_[size_t(slots_[s].patch)].invalid = true;
      if (slots_[s].follower >= 0) ps_[size_t(slots_[size_t(slots_[s].follower)].patch)].invalid = true;
      discretize(int(s));
      if (round > 0) ++invalidations_;
    }
  if (round == 0 && o_.adaptation) {
    adaptAcrossShared();
    flushSources();
  }
}

// 5-12: section 3.2 on each patch whose boundary was discretized or whose control space
// changed since its last check; the updates are inserted afterwards.
bool ModelMesher::checkBoundaries(int /*round*/) {
  for (size_t p = 0; p < ps_.size(); ++p)
    if (ps_[p].invalid || ps_[p].modified) {
      ps_[p].modified = false;
      try {
        checkPatchBoundary(int(p));
      } catch (const Error& e) {
        throw Error(e.code(), patchLabel(m_.patches[p], int(p)) + ": " + e.what());
      }
      ps_[p].invalid = false;
    }
  bool changed = false;
  for (const auto& pending : pending_) changed = changed || !pending.empty();
  flushSources();
  return changed;
}

bool ModelMesher::hasStaleInvalidContour() const {
  for (const Slot& s : slots_)
    if (s.invalid && s.master < 0) return true;
  return false;
}

// 14-15: the patches' interiors, concurrently when there are several and their control
// spaces allow it (each patch's mesh is the same either way; an error is the lowest
// patch's, as when they are meshed in order). One progress for all, the patches' mean,
// reported from the calling thread only (its own patch's ticks, then parallelChunks' poll):
// a callback bound to its thread (a JS function in the pthreads build) stays there.
std::vector<Mesh> ModelMesher::meshPatchInteriors(const std::vector<std::vector<BoundaryLoop>>& loops) {
  const size_t n = m_.patches.size();
  std::vector<Mesh> meshes(n);
  bool concurrent = n > 1;
  for (size_t p = 0; p < n; ++p) concurrent = concurrent && queriesAreConcurrent(space(int(p)));
  // The patches' options, made here without the caller's callback (copying it on another
  // thread could touch what only this thread may).
  PlanarMesherOptions base = o_.mesher;
  base.progress = nullptr;
  base.boundaryOnly = false;
  // Quads are merged in the patch's (u, v) (never across its contour edges); the all-quad
  // split is done in meshPatches so that shared contour edges get one midpoint for both.
  base.quads = o_.quads || o_.allQuads;
  base.allQuads = false;
  CallerProgress progress(n, o_.mesher.progress);
  auto meshPatch = [&](size_t p) {
    PlanarMesherOptions mo = base;
    mo.boundaryCache = boundaryCaches_[p];
    if (o_.mesher.progress) {
      if (n == 1) {
        mo.progress = o_.mesher.progress;  // (this thread)
      } else {
        mo.progress = progress.task(p);
      }
    }
    try {
      meshes[p] = meshPlanarBoundary(loops[p], space(int(p)), mo);
    } catch (const Error& e) {
      throw Error(e.code(), patchLabel(m_.patches[p], int(p)) + ": " + e.what());
    }
  };
  if (concurrent)
    parallelChunks(
        n, 1, [&](size_t p, size_t, size_t) { meshPatch(p); },
        o_.mesher.progress ? progress.poll() : std::function<void()>());
  else
    for (size_t p = 0; p < n; ++p) meshPatch(p);
  return meshes;
}

// 14-16: inner nodes and improvement per patch; merge.
Mesh ModelMesher::meshPatches() {
  SurfaceMeshReport* report = report_;
  Mesh out;
  out.dimension = 3;
  std::vector<int> defined(size_t(nextId_), -1);  // patch that placed each merged boundary vertex
  out.points.resize(size_t(nextId_));
  out.params.resize(size_t(nextId_));
  std::set<std::array<int, 2>> sharedEdges;
  std::vector<int> patchTriangles, patchQuads;
  std::vector<MeasuredPatch> measured;            // what the 3D measures read (surface_measures.cpp)
  std::map<std::array<int, 2>, int> boundaryMid;  // all-quad: merged point splitting a contour edge
  const size_t patches = m_.patches.size();
  std::vector<std::vector<BoundaryLoop>> patchLoops(patches);
  std::vector<std::vector<int>> patchIds(patches);
  std::vector<std::vector<char>> patchShared(patches);
  for (size_t p = 0; p < patches; ++p) patchLoops[p] = loopsOf(int(p), &patchIds[p], &patchShared[p], o_.allQuads);
  std::vector<Mesh> patchMeshes = meshPatchInteriors(patchLoops);
  for (size_t p = 0; p < patches; ++p) {
    const SurfacePatch& patch = m_.patches[p];
    const Surface& surf = *patch.surface;
    const std::vector<int>& ids = patchIds[p];
    const std::vector<char>& shared = patchShared[p];
    const std::vector<BoundaryLoop>& loops = patchLoops[p];
    Mesh pm = std::move(patchMeshes[p]);
    const size_t nb = ids.size();
    if (pm.params.size() != pm.points.size()) {  // (the planar mesher fills params; keep the fallback)
      pm.params.clear();
      for (const Vec3& x : pm.points) pm.params.push_back(x.head<2>());
    }
    // Loop edges: boundary point i to next[i].
    std::vector<int> next(nb);
    {
      size_t base = 0;
      for (const auto& loop : loops) {
        const size_t n = loop.points.size();
        for (size_t i = 0; i < n; ++i) next[base + i] = int(base + (i + 1) % n);
        base += n;
      }
    }
    // A merged quad is not flat: where its two triangulations leave the surface by more
    // than the chord tolerance, the merge is undone (the pair it came from, diagonal 1-3),
    // so quad-dominant meshes keep the tolerance the triangles were sized for.
    if (!pm.quads.empty() && o_.metric.chordTolerance > 0) {
      std::vector<std::array<int, 4>> kept;
      for (const auto& qd : pm.quads) {
        Vec2 u[4];
        Vec3 x[4];
        for (int k = 0; k < 4; ++k) u[k] = pm.params[size_t(qd[size_t(k)])], x[k] = surf.point(u[k]);
        double dev = 0.0;
        for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}, std::array<int, 3>{0, 1, 3},
                                std::array<int, 3>{1, 2, 3}}) {
          const Vec2 tu[3] = {u[tri[0]], u[tri[1]], u[tri[2]]};
          const Vec3 tx[3] = {x[tri[0]], x[tri[1]], x[tri[2]]};
          dev = std::max(dev, normalTriangleDeviation(surf, tu, tx));
        }
        if (dev <= o_.metric.chordTolerance) {
          kept.push_back(qd);
        } else {
          pm.triangles.push_back({qd[0], qd[1], qd[3]});
          pm.triangles.push_back({qd[1], qd[2], qd[3]});
        }
      }
      pm.quads = std::move(kept);
    }
    const size_t nBefore = pm.params.size();
    std::vector<std::array<int, 2>> splits;
    if (o_.allQuads) splits = splitIntoAllQuads(pm, loopEdgeMidpoints(loops));
    std::vector<int> gid(pm.params.size());
    for (size_t i = 0; i < pm.params.size(); ++i) {
      const Vec2 uv = pm.params[i];
      int g = -1;
      const std::array<int, 2> from = i >= nBefore ? splits[i - nBefore] : std::array<int, 2>{-1, -1};
      std::array<int, 2> key{-1, -1};
      if (from[0] >= 0 && o_.mergeMesh) {
        key = {std::min(ids[size_t(from[0])], ids[size_t(from[1])]),
               std::max(ids[size_t(from[0])], ids[size_t(from[1])])};
        const auto it = boundaryMid.find(key);
        if (it != boundaryMid.end()) g = it->second;
      }
      if (i < nb && o_.mergeMesh)
        g = ids[i];
      else if (g < 0) {
        g = int(out.points.size());
        out.points.emplace_back();
        out.params.emplace_back();
        defined.push_back(-1);
        if (key[0] >= 0) boundaryMid[key] = g;
      }
      gid[i] = g;
      if (defined[size_t(g)] < 0) {
        const Vec3 x = surf.point(uv);
        if (!x.allFinite())  // (not require(): the message would be formatted for every vertex)
          throw Error(ErrorCode::InvalidSurface,
                      patchLabel(patch, int(p)) + ": S(u, v) is NaN or infinite at " + fmtUv(uv));
        out.points[size_t(g)] = x;
        out.params[size_t(g)] = uv;
        defined[size_t(g)] = int(p);
      }
    }
    // Boundary edges (split in two for all-quad): shared ones are interior to the merged mesh.
    {
      std::map<std::array<int, 2>, int> localMid;
      for (size_t k = 0; k < splits.size(); ++k)
        if (splits[k][0] >= 0) localMid[splits[k]] = int(nBefore + k);
      size_t base = 0;
      for (const auto& loop : loops) {
        const size_t n = loop.points.size();
        for (size_t i = 0; i < n; ++i) {
          std::vector<int> chain{gid[base + i]};
          const auto it = localMid.find({int(base + i), next[base + i]});
          if (it != localMid.end()) chain.push_back(gid[size_t(it->second)]);
          chain.push_back(gid[size_t(next[base + i])]);
          for (size_t c = 0; c + 1 < chain.size(); ++c) {
            const int a = chain[c], b = chain[c + 1];
            const std::array<int, 2> e{std::min(a, b), std::max(a, b)};
            if (shared[base + i] && o_.mergeMesh)
              sharedEdges.insert(e);
            else {
              out.edges.push_back({a, b});
              out.edgeRefs.push_back(loop.edgeRefs[i]);
            }
          }
        }
        base += n;
      }
    }
    for (const auto& t : pm.triangles) {
      out.triangles.push_back({gid[size_t(t[0])], gid[size_t(t[1])], gid[size_t(t[2])]});
      out.triangleRefs.push_back(patch.id);
    }
    for (const auto& t : pm.quads) {
      out.quads.push_back({gid[size_t(t[0])], gid[size_t(t[1])], gid[size_t(t[2])], gid[size_t(t[3])]});
      out.quadRefs.push_back(patch.id);
    }
    patchTriangles.push_back(int(pm.triangles.size()));
    patchQuads.push_back(int(pm.quads.size()));
    if (o_.measureQuality)
      measured.push_back({patch.surface, &space(int(p)), std::move(pm.params), std::move(pm.triangles),
                          std::move(pm.quads), std::move(gid)});
  }
  if (o_.consistentOrientation) orientPatches(out, patchTriangles, patchQuads, sharedEdges);
  // Drop merged ids left over from earlier discretizations (never placed).
  {
    std::vector<int> remap(out.points.size(), -1);
    std::vector<Vec3> pts;
    std::vector<Vec2> prm;
    for (size_t i = 0; i < out.points.size(); ++i)
      if (defined[i] >= 0) {
        remap[i] = int(pts.size());
        pts.push_back(out.points[i]);
        prm.push_back(out.params[i]);
      }
    out.points = std::move(pts);
    out.params = std::move(prm);
    for (auto& t : out.triangles)
      for (int& v : t) v = remap[size_t(v)];
    for (auto& t : out.quads)
      for (int& v : t) v = remap[size_t(v)];
    for (auto& e : out.edges)
      for (int& v : e) v = remap[size_t(v)];
    std::set<std::array<int, 2>> se;
    for (const auto& e : sharedEdges) {
      const int a = remap[size_t(e[0])], b = remap[size_t(e[1])];
      se.insert({std::min(a, b), std::max(a, b)});
    }
    sharedEdges = std::move(se);
    for (auto& mp : measured)
      for (int& g : mp.gid) g = remap[size_t(g)];
  }
  out.pointRefs.assign(out.points.size(), 0);

  // The 3D measures: now, or kept for finishSurfaceMeasures() (with the patch states
  // whose control spaces they query).
  std::shared_ptr<DeferredMeasures> measures;
  if (o_.measureQuality) {
    measures = std::make_shared<DeferredMeasures>();
    measures->counters = counters_;
    measures->patches = std::move(measured);
    measures->points = out.points;
    measures->chordTolerance = o_.metric.chordTolerance;
    if (!(o_.deferQuality && report)) {
      measures->measureElements();
      measures->measureChords();
    }
  }
  if (report) {
    if (o_.controlSpaceGlyphs) report->controlSpaceGlyphs = glyphs();
    report->patches = int(m_.patches.size());
    report->vertices = out.vertexCount();
    report->triangles = int(out.triangles.size());
    report->sharedEdgeList.assign(sharedEdges.begin(), sharedEdges.end());
    report->sharedEdges = int(sharedEdges.size());
    report->crossSharedSizeRatioMax = acrossEdgeSizeRatio(out, report->sharedEdgeList);
    report->curvatureEvaluations = counters_->curvature();
    report->curvatureSeconds = counters_->curvatureSeconds();
    report->controlSpaceQueries = counters_->queries();
    report->controlSpaceSeconds = counters_->querySeconds();
    report->patchTriangles = patchTriangles;
    if (measures && measures->chordsDone) {
      measures->fill(*report);
    } else if (measures) {
      measures->states = std::move(ps_);  // (the mesher is done with them)
      report->deferred = std::move(measures);
    }
  }
  return out;
}

}  // namespace surface_mesher

Mesh meshSurfaceModel(const SurfaceModel& model, const SurfaceMeshOptions& options, SurfaceMeshReport* report) {
  surface_mesher::ModelMesher mesher(model, options);
  return mesher.run(report);
}

Mesh meshSurfacePatch(const SurfacePatch& patch, const SurfaceMeshOptions& options, SurfaceMeshReport* report) {
  SurfaceModel m;
  m.patches.push_back(patch);
  return meshSurfaceModel(m, options, report);
}

}  // namespace anisomesh

// Planar mesher: the boundary triangulation a boundary-only run (a section 3.2 check)
// leaves for the full run on the same loops, which would otherwise build it again: on a
// curved contour inserted in loop order that build is a tenth of the patch's meshing.
#include "mesher_impl.h"

namespace anisomesh {

// The loops and every member of the mesher that triangulateBoundary() and removeOutside()
// write (the mesh and the kernel's scratch, epochs included): a full run given it continues
// exactly as one that built them. Moved in and out, never copied.
struct BoundaryTriangulationCache {
  bool filled = false;
  std::vector<BoundaryLoop> loops;
  std::vector<planar::Mesher::Vtx> vx;
  std::vector<std::uint8_t> vbnd;
  std::vector<int> vtri;
  std::vector<planar::Mesher::Tri> tri;
  std::vector<int> freeTris;
  std::vector<std::array<int, 2>> bedges;
  std::vector<int> bedgeRefs;
  int nBoundary = 0;
  std::vector<std::uint32_t> forbid, vmark;
  std::uint32_t epoch = 0, fepoch = 0;
  std::vector<int> cav;
  std::vector<planar::Mesher::BndEdge> bnd;
  std::vector<int> startAt, endAt, newTris;
  std::uint32_t rng = 0;
  std::vector<planar::TriCache> cache;
  std::vector<std::uint32_t> stamp, queued;

  static bool sameLoops(const std::vector<BoundaryLoop>& a, const std::vector<BoundaryLoop>& b) {
    if (a.size() != b.size()) return false;
    for (size_t k = 0; k < a.size(); ++k)
      if (a[k].points != b[k].points || a[k].edgeRefs != b[k].edgeRefs || a[k].edgeMidpoints != b[k].edgeMidpoints)
        return false;
    return true;
  }

  // Takes the state of a finished boundary-only run (moved: that mesher is done with it).
  void take(planar::Mesher& m) {
    loops = m.loops_;
    vx = std::move(m.vx_), vbnd = std::move(m.vbnd_), vtri = std::move(m.vtri_), tri = std::move(m.tri_);
    freeTris = std::move(m.freeTris_), bedges = std::move(m.bedges_), bedgeRefs = std::move(m.bedgeRefs_);
    nBoundary = m.nBoundary_;
    forbid = std::move(m.forbid_), vmark = std::move(m.vmark_), epoch = m.epoch_, fepoch = m.fepoch_;
    cav = std::move(m.cav_), bnd = std::move(m.bnd_), startAt = std::move(m.startAt_), endAt = std::move(m.endAt_);
    newTris = std::move(m.newTris_), rng = m.rng_;
    cache = std::move(m.cache_), stamp = std::move(m.stamp_), queued = std::move(m.queued_);
    filled = true;
  }

  // Gives it to a full run (moved: used once).
  void give(planar::Mesher& m) {
    m.vx_ = std::move(vx), m.vbnd_ = std::move(vbnd), m.vtri_ = std::move(vtri), m.tri_ = std::move(tri);
    m.freeTris_ = std::move(freeTris), m.bedges_ = std::move(bedges), m.bedgeRefs_ = std::move(bedgeRefs);
    m.nBoundary_ = nBoundary;
    m.forbid_ = std::move(forbid), m.vmark_ = std::move(vmark), m.epoch_ = epoch, m.fepoch_ = fepoch;
    m.cav_ = std::move(cav), m.bnd_ = std::move(bnd), m.startAt_ = std::move(startAt), m.endAt_ = std::move(endAt);
    m.newTris_ = std::move(newTris), m.rng_ = rng;
    m.cache_ = std::move(cache), m.stamp_ = std::move(stamp), m.queued_ = std::move(queued);
    filled = false;
    loops.clear();
  }
};

std::shared_ptr<BoundaryTriangulationCache> makeBoundaryTriangulationCache() {
  return std::make_shared<BoundaryTriangulationCache>();
}

namespace planar {

void Mesher::boundaryTriangulation() {
  BoundaryTriangulationCache* cache = opt_.boundaryCache.get();
  if (cache && !opt_.boundaryOnly && cache->filled && BoundaryTriangulationCache::sameLoops(cache->loops, loops_)) {
    cache->give(*this);
    timings_.boundaryFromCache = true;
    return;
  }
  triangulateBoundary();
  removeOutside();
}

void Mesher::keepBoundaryTriangulation() {
  // After a boundary-only run, the state differs from the one boundaryTriangulation() left
  // only in the vertex metrics, which a full run queries again.
  if (opt_.boundaryCache && opt_.boundaryOnly) opt_.boundaryCache->take(*this);
}

}  // namespace planar
}  // namespace anisomesh

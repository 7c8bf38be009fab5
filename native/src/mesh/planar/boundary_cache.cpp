// Planar mesher: the boundary triangulation a boundary-only run (a section 3.2 check)
// leaves for the full run on the same loops, which would otherwise build it again: on a
// curved contour inserted in loop order that build is a tenth of the patch's meshing.
#include "mesher_impl.h"

namespace anisomesh {

// The loops and every member of the mesher that triangulateBoundary() and removeOutside()
// write (the mesh and the kernel's scratch, epochs included): a full run restored from it
// continues exactly as one that built them.
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

  void save(const planar::Mesher& m) {
    loops = m.loops_;
    vx = m.vx_, vbnd = m.vbnd_, vtri = m.vtri_, tri = m.tri_, freeTris = m.freeTris_;
    bedges = m.bedges_, bedgeRefs = m.bedgeRefs_, nBoundary = m.nBoundary_;
    forbid = m.forbid_, vmark = m.vmark_, epoch = m.epoch_, fepoch = m.fepoch_;
    cav = m.cav_, bnd = m.bnd_, startAt = m.startAt_, endAt = m.endAt_, newTris = m.newTris_, rng = m.rng_;
    cache = m.cache_, stamp = m.stamp_, queued = m.queued_;
    filled = true;
  }

  void restore(planar::Mesher& m) const {
    m.vx_ = vx, m.vbnd_ = vbnd, m.vtri_ = vtri, m.tri_ = tri, m.freeTris_ = freeTris;
    m.bedges_ = bedges, m.bedgeRefs_ = bedgeRefs, m.nBoundary_ = nBoundary;
    m.forbid_ = forbid, m.vmark_ = vmark, m.epoch_ = epoch, m.fepoch_ = fepoch;
    m.cav_ = cav, m.bnd_ = bnd, m.startAt_ = startAt, m.endAt_ = endAt, m.newTris_ = newTris, m.rng_ = rng;
    m.cache_ = cache, m.stamp_ = stamp, m.queued_ = queued;
  }
};

std::shared_ptr<BoundaryTriangulationCache> makeBoundaryTriangulationCache() {
  return std::make_shared<BoundaryTriangulationCache>();
}

namespace planar {

void Mesher::boundaryTriangulation() {
  BoundaryTriangulationCache* cache = opt_.boundaryCache.get();
  if (cache && !opt_.boundaryOnly && cache->filled && BoundaryTriangulationCache::sameLoops(cache->loops, loops_)) {
    cache->restore(*this);
    timings_.boundaryFromCache = true;
    return;
  }
  triangulateBoundary();
  removeOutside();
  if (cache && opt_.boundaryOnly) cache->save(*this);
}

}  // namespace planar
}  // namespace anisomesh

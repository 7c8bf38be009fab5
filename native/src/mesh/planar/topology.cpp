// Planar mesher: input checks, triangle storage and adjacency, progress, output mesh.
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

void Mesher::validate() const {
  require(!loops_.empty(), ErrorCode::InvalidArgument, "meshPlanarBoundary: no boundary loop given");
  for (size_t l = 0; l < loops_.size(); ++l) {
    const auto& lp = loops_[l];
    const std::string name = l == 0 ? "outer loop" : "hole loop " + std::to_string(l);
    require(
        lp.points.size() >= 3, ErrorCode::InvalidArgument,
        "meshPlanarBoundary: " + name + " has " + std::to_string(lp.points.size()) + " points, at least 3 are needed");
    require(lp.edgeRefs.size() == lp.points.size(), ErrorCode::InvalidArgument,
            "meshPlanarBoundary: " + name + " has " + std::to_string(lp.points.size()) + " points but " +
                std::to_string(lp.edgeRefs.size()) + " edge refs (one per edge expected)");
    require(lp.edgeMidpoints.empty() || lp.edgeMidpoints.size() == lp.points.size(), ErrorCode::InvalidArgument,
            "meshPlanarBoundary: " + name + " has " + std::to_string(lp.points.size()) + " points but " +
                std::to_string(lp.edgeMidpoints.size()) + " edge midpoints (none or one per edge expected)");
    for (const Vec2& m : lp.edgeMidpoints)
      require(m.allFinite(), ErrorCode::InvalidArgument,
              "meshPlanarBoundary: " + name + " has a non-finite edge midpoint");
    for (size_t i = 0; i < lp.points.size(); ++i)
      require(lp.points[i].allFinite(), ErrorCode::InvalidArgument,
              "meshPlanarBoundary: " + name + " point " + std::to_string(i) + " is not finite");
  }
  require(opt_.maxElements > 0, ErrorCode::InvalidArgument, "meshPlanarBoundary: maxElements must be positive");
  require(opt_.improvementPasses >= 0, ErrorCode::InvalidArgument,
          "meshPlanarBoundary: improvementPasses must be >= 0");
  require(std::isfinite(opt_.minNodeDistance) && opt_.minNodeDistance >= 0.0 && opt_.minNodeDistance < 1.0,
          ErrorCode::InvalidArgument, "meshPlanarBoundary: minNodeDistance must be in [0, 1)");
  require(std::isfinite(opt_.minQuadQuality) && opt_.minQuadQuality > 0.0 && opt_.minQuadQuality <= 1.0,
          ErrorCode::InvalidArgument, "meshPlanarBoundary: minQuadQuality must be in (0, 1]");
}

void Mesher::checkProgress(double fraction) {
  lastFraction_ = std::min(1.0, std::max(0.0, fraction));
  if (opt_.progress && !opt_.progress(lastFraction_))
    throw Error(ErrorCode::Cancelled, "meshPlanarBoundary: cancelled by the progress callback");
}

bool Mesher::closedBall(int v, std::vector<int>& tris, std::vector<int>& ring) const {
  tris.clear();
  ring.clear();
  const int t0 = vtri_[v];
  int t = t0;
  for (int guard = 0; guard < 1000; ++guard) {
    const auto& tv = tri_[t].v;
    const int i = tv[0] == v ? 0 : (tv[1] == v ? 1 : 2);
    tris.push_back(t);
    ring.push_back(tv[next3(i)]);
    t = tri_[t].n[next3(i)];
    if (t < 0 || t == t0) break;
  }
  return t == t0;
}

void Mesher::ballMetrics(int v, const std::vector<int>& ring, std::vector<SymMt>& edgeM,
                         std::vector<SymMt>& triM) const {
  const size_t deg = ring.size();
  edgeM.resize(deg);
  triM.resize(deg);
  for (size_t k = 0; k < deg; ++k) {
    edgeM[k] = SymMt::average2(vx_[v].m, vx_[ring[k]].m);
    triM[k] = SymMt::average3(vx_[v].m, vx_[ring[k]].m, vx_[ring[k + 1 == deg ? 0 : k + 1]].m);
  }
}

int Mesher::allocTri() {
  if (!freeTris_.empty()) {
    const int t = freeTris_.back();
    freeTris_.pop_back();
    ++stamp_[t];
    return t;
  }
  tri_.push_back(Tri{{-1, -1, -1}, {-1, -1, -1}, 0, 0, 0});
  stamp_.push_back(0);
  if (!improving_) {  // the cavity and frontal state: not used after the insertion
    forbid_.push_back(0);
    queued_.push_back(std::numeric_limits<std::uint32_t>::max());
    cache_.emplace_back();
  }
  return static_cast<int>(tri_.size()) - 1;
}

void Mesher::setNbrAcross(int tri, int a, int b, int newNbr) {
  if (tri < 0) return;
  auto& v = tri_[tri].v;
  for (int j = 0; j < 3; ++j)
    if (v[next3(j)] == b && v[prev3(j)] == a) {
      tri_[tri].n[j] = newNbr;
      return;
    }
  throw Error(ErrorCode::Internal, "meshPlanarBoundary: broken triangle adjacency");
}

int Mesher::findEdge(int a, int b, int* idx) const {
  // Rotate around a (all vertices touched here are interior to the super-box triangulation
  // or the rotation stops at a hull edge, which is then walked the other way).
  const int t0 = vtri_[a];
  int t = t0;
  for (int guard = 0; guard < 100000; ++guard) {
    const auto& v = tri_[t].v;
    const int i = v[0] == a ? 0 : (v[1] == a ? 1 : 2);
    if (v[next3(i)] == b) {
      *idx = prev3(i);
      return t;
    }
    // Next triangle counter-clockwise around a: across edge (a, v[prev]) opposite v[next].
    t = tri_[t].n[next3(i)];
    if (t < 0 || t == t0) break;
  }
  if (t < 0) {  // hit a hull edge: go clockwise from the start
    t = t0;
    for (int guard = 0; guard < 100000; ++guard) {
      const auto& v = tri_[t].v;
      const int i = v[0] == a ? 0 : (v[1] == a ? 1 : 2);
      if (v[next3(i)] == b) {
        *idx = prev3(i);
        return t;
      }
      t = tri_[t].n[prev3(i)];
      if (t < 0 || t == t0) break;
    }
  }
  return -1;
}

Mesh Mesher::output() const {
  Mesh m;
  m.dimension = 2;
  // Removed (collapsed) vertices are skipped; boundary vertices keep their places first.
  std::vector<int> vmap(vx_.size(), -1);
  int nv = 0;
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v)
    if (vbnd_[v] != 2) vmap[v] = nv++;
  m.points.reserve(nv);
  m.params.reserve(nv);
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v) {
    if (vmap[v] < 0) continue;
    m.points.emplace_back(vx_[v].p.x(), vx_[v].p.y(), 0.0);
    m.params.push_back(vx_[v].p);
  }
  m.pointRefs.assign(nv, 0);
  for (size_t e = 0; e < bedges_.size(); ++e) {
    m.edges.push_back({vmap[bedges_[e][0]], vmap[bedges_[e][1]]});
    m.edgeRefs.push_back(bedgeRefs_[e]);
  }
  m.triangles.reserve(tri_.size());
  for (const auto& tr : tri_) {
    const auto& t = tr.v;
    if (t[0] < 0) continue;
    m.triangles.push_back({vmap[t[0]], vmap[t[1]], vmap[t[2]]});
  }
  m.triangleRefs.assign(m.triangles.size(), 0);
  return m;
}

}  // namespace planar
}  // namespace anisomesh

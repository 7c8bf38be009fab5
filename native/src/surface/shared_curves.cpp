// Surface meshing: the boundary curves of every patch (slots), curves shared by two patches
// (matched in 3D, discretized once), contour discretization and boundary loops, adaptation
// of neighbouring control spaces across shared curves.
#include "model_mesher.h"

namespace anisomesh {
namespace surface_mesher {

namespace {

// Nearest-point map from 3D onto a curve of a patch: coarse table, then golden section.
class CurveProjector {
 public:
  CurveProjector(const SurfaceModel& m, const Slot& s) : m_(m), s_(s) {
    for (int i = 0; i <= kN; ++i) pts_.push_back(slotPoint(m, s, double(i) / kN));
  }
  // Parameter of the point of the curve nearest to x; *dist receives the distance.
  double project(const Vec3& x, double* dist = nullptr) const {
    int best = 0;
    double bd = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kN; ++i) {
      const double d = (pts_[size_t(i)] - x).squaredNorm();
      if (d < bd) bd = d, best = i;
    }
    double lo = double(std::max(best - 1, 0)) / kN, hi = double(std::min(best + 1, kN)) / kN;
    auto f = [&](double t) { return (slotPoint(m_, s_, t) - x).squaredNorm(); };
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double a = hi - g * (hi - lo), b = lo + g * (hi - lo), fa = f(a), fb = f(b);
    for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) {
      if (fa < fb)
        hi = b, b = a, fb = fa, a = hi - g * (hi - lo), fa = f(a);
      else
        lo = a, a = b, fa = fb, b = lo + g * (hi - lo), fb = f(b);
    }
    double t = 0.5 * (lo + hi);
    // Ends are exact matches of corners: snap when the table's end is the best.
    for (double e : {0.0, 1.0})
      if (f(e) <= f(t)) t = e;
    if (dist) *dist = std::sqrt(f(t));
    return t;
  }

 private:
  static constexpr int kN = 256;
  const SurfaceModel& m_;
  const Slot& s_;
  std::vector<Vec3> pts_;
};

}  // namespace

void ModelMesher::setupSlots() {
  ps_.resize(m_.patches.size());
  pending_.resize(m_.patches.size());
  boundaryCaches_.resize(m_.patches.size());
  for (auto& c : boundaryCaches_) c = makeBoundaryTriangulationCache();
  for (size_t p = 0; p < m_.patches.size(); ++p) {
    const SurfacePatch& patch = m_.patches[p];
    for (int k = 0; k < contourCount(patch); ++k) {
      const Contour& c = contourOf(patch, k);
      ps_[p].slots.emplace_back();
      const int n = int(c.curves.size());
      for (int j = 0; j < n; ++j) {
        Slot s;
        s.patch = int(p), s.contour = k, s.curve = j;
        s.c = c.curves[size_t(j)].curve;
        s.minSegments = n == 1 ? 3 : n == 2 ? 2 : 1;
        ps_[p].slots.back().push_back(int(slots_.size()));
        slots_.push_back(std::move(s));
      }
    }
  }
  auto find = [&](const CurveRef& r, const std::string& what) {
    require(r.patch >= 0 && r.patch < int(m_.patches.size()), ErrorCode::InvalidArgument,
            what + ": no patch " + std::to_string(r.patch));
    const auto& cs = ps_[size_t(r.patch)].slots;
    require(r.contour >= 0 && r.contour < int(cs.size()), ErrorCode::InvalidArgument,
            what + ": " + patchLabel(m_.patches[size_t(r.patch)], r.patch) + " has no contour " +
                std::to_string(r.contour));
    require(r.curve >= 0 && r.curve < int(cs[size_t(r.contour)].size()), ErrorCode::InvalidArgument,
            what + ": " + patchLabel(m_.patches[size_t(r.patch)], r.patch) + " " + contourName(r.contour) +
                " has no curve " + std::to_string(r.curve));
    return cs[size_t(r.contour)][size_t(r.curve)];
  };
  for (size_t k = 0; k < m_.shared.size(); ++k) {
    const std::string what = "shared[" + std::to_string(k) + "]";
    const int a = find(m_.shared[k].a, what), b = find(m_.shared[k].b, what);
    require(a != b, ErrorCode::InvalidArgument, what + ": a curve cannot be shared with itself");
    for (int s : {a, b})
      require(slots_[size_t(s)].master < 0 && slots_[size_t(s)].follower < 0, ErrorCode::InvalidArgument,
              what + ": " + slotName(m_, slots_[size_t(s)]) + " is already shared");
    slots_[size_t(a)].follower = b;
    slots_[size_t(b)].master = a;
    slots_[size_t(b)].masterReversed = m_.shared[k].reversed;
    slots_[size_t(a)].minSegments = slots_[size_t(b)].minSegments =
        std::max(slots_[size_t(a)].minSegments, slots_[size_t(b)].minSegments);
  }
}

// Shared curves must be the same curve in 3D (sampled both ways).
void ModelMesher::validateSharing() {
  const double tol = o_.sharedTolerance * size_;
  for (const Slot& b : slots_) {
    if (b.master < 0) continue;
    const Slot& a = slots_[size_t(b.master)];
    auto mismatch = [&](const Slot& x, const Slot& y, double t, double d) {
      throw Error(ErrorCode::InvalidSurface, "shared curve mismatch: " + slotName(m_, x) + " and " + slotName(m_, y) +
                                                 " are " + fmt(d) + " apart (tolerance " + fmt(tol) +
                                                 ") at t = " + fmt(t) + ", " + fmtUv(x.c->point(t)) + " of " +
                                                 patchLabel(m_.patches[size_t(x.patch)], x.patch));
    };
    for (int end = 0; end < 2; ++end) {
      const double ta = end, tb = b.masterReversed ? 1.0 - end : double(end);
      const double d = (slotPoint(m_, a, ta) - slotPoint(m_, b, tb)).norm();
      if (d > tol) mismatch(a, b, ta, d);
    }
    const CurveProjector pa(m_, a), pb(m_, b);
    for (int i = 1; i < 16; ++i) {
      const double t = i / 16.0;
      double d;
      pb.project(slotPoint(m_, a, t), &d);
      if (d > tol) mismatch(a, b, t, d);
      pa.project(slotPoint(m_, b, t), &d);
      if (d > tol) mismatch(b, a, t, d);
    }
  }
}

// Curve ends: one merged vertex per corner, joined along contours and through sharing.
void ModelMesher::assignCornerIds() {
  const int n = int(slots_.size());
  std::vector<int> parent(size_t(2 * n));
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int x) {
    return parent[size_t(x)] == x ? x : parent[size_t(x)] = root(parent[size_t(x)]);
  };
  auto unite = [&](int x, int y) { parent[size_t(root(x))] = root(y); };
  for (size_t p = 0; p < m_.patches.size(); ++p)
    for (int k = 0; k < contourCount(m_.patches[p]); ++k) {
      const Contour& c = contourOf(m_.patches[p], k);
      const auto& ids = ps_[p].slots[size_t(k)];
      const int cnt = int(ids.size());
      for (int j = 0; j < cnt; ++j) {
        const int jn = (j + 1) % cnt;
        const int exitEnd = c.curves[size_t(j)].reversed ? 0 : 1;
        const int entryEnd = c.curves[size_t(jn)].reversed ? 1 : 0;
        unite(2 * ids[size_t(j)] + exitEnd, 2 * ids[size_t(jn)] + entryEnd);
      }
    }
  for (int s = 0; s < n; ++s) {
    const Slot& b = slots_[size_t(s)];
    if (b.master < 0) continue;
    unite(2 * b.master + 0, 2 * s + (b.masterReversed ? 1 : 0));
    unite(2 * b.master + 1, 2 * s + (b.masterReversed ? 0 : 1));
  }
  std::map<int, int> idOf;
  for (int e = 0; e < 2 * n; ++e)
    if (!idOf.count(root(e))) idOf[root(e)] = nextId_++;
  for (int s = 0; s < n; ++s) slots_[size_t(s)].gid = {idOf[root(2 * s)], idOf[root(2 * s + 1)]};
}

// Shared curve: per piece of a (between its corners), the metric length density is the
// larger of the two patches' at each sample (stricter metric); points at equal length.
std::vector<double> ModelMesher::discretizeShared(const Slot& a, const Slot& b, std::vector<double>* tb) {
  const CurveProjector proj(m_, b);
  const ControlSpace& csa = space(a.patch);
  const ControlSpace& csb = space(b.patch);
  std::vector<double> bounds{0.0};
  for (double t : a.c->breakpoints())
    if (t > bounds.back() && t < 1.0) bounds.push_back(t);
  bounds.push_back(1.0);
  auto mapB = [&](double t) { return proj.project(slotPoint(m_, a, t)); };

  std::vector<double> ts{0.0};
  int pieceSegments = 0;
  std::vector<std::vector<double>> pieceT, pieceCum;
  for (size_t k = 0; k + 1 < bounds.size(); ++k) {
    int samples = 32;
    std::vector<double> t, cum;
    for (int pass = 0; pass < 2; ++pass) {
      t.assign(size_t(samples) + 1, 0.0);
      cum.assign(size_t(samples) + 1, 0.0);
      Vec2 ua = a.c->point(bounds[k]), ub = b.c->point(mapB(bounds[k]));
      for (int i = 0; i <= samples; ++i) {
        t[size_t(i)] = bounds[k] + (bounds[k + 1] - bounds[k]) * i / samples;
        if (i == 0) continue;
        const Vec2 na = a.c->point(t[size_t(i)]), nb = b.c->point(mapB(t[size_t(i)]));
        const double la = csa.metricAt(0.5 * (ua + na)).length(na - ua);
        const double lb = csb.metricAt(0.5 * (ub + nb)).length(nb - ub);
        cum[size_t(i)] = cum[size_t(i - 1)] + std::max(la, lb);
        ua = na, ub = nb;
      }
      const double len = cum.back();
      require(std::isfinite(len), ErrorCode::InvalidMetric, "metric length of " + slotName(m_, a) + " is not finite");
      const int want = int(std::min(20000.0, std::ceil(8.0 * len)));
      if (want <= samples) break;
      samples = want;
    }
    pieceSegments += int(std::max(1.0, std::round(cum.back())));
    pieceT.push_back(std::move(t));
    pieceCum.push_back(std::move(cum));
  }
  const int extra = std::max(0, a.minSegments - pieceSegments);
  for (size_t k = 0; k < pieceT.size(); ++k) {
    const auto& t = pieceT[k];
    const auto& cum = pieceCum[k];
    int n = int(std::max(1.0, std::round(cum.back())));
    if (k == 0) n += extra;
    require(std::int64_t(n) <= o_.mesher.maxElements, ErrorCode::ElementBudgetExceeded,
            "discretizing " + slotName(m_, a) + " exceeds the element budget");
    size_t j = 1;
    for (int i = 1; i < n; ++i) {
      const double target = cum.back() * i / n;
      while (j + 1 < cum.size() && cum[j] < target) ++j;
      const double w = cum[j] > cum[j - 1] ? (target - cum[j - 1]) / (cum[j] - cum[j - 1]) : 0.5;
      ts.push_back(std::max(ts.back(), t[j - 1] + w * (t[j] - t[j - 1])));
    }
    ts.push_back(bounds[k + 1]);
  }
  tb->clear();
  for (size_t i = 0; i < ts.size(); ++i) {
    if (i == 0 || i + 1 == ts.size())
      tb->push_back((i == 0) != b.masterReversed ? 0.0 : 1.0);
    else
      tb->push_back(mapB(ts[i]));
  }
  return ts;
}

void ModelMesher::discretize(int si) {
  Slot& s = slots_[size_t(si)];
  const int first = s.gid.front(), last = s.gid.back();
  std::vector<int> gid{first};
  if (s.follower < 0) {
    DiscretizeOptions d;
    d.maxSegments = std::max<std::int64_t>(1, o_.mesher.maxElements);
    s.t = discretizeCurve(*s.c, space(s.patch), s.minSegments, d);
  } else {
    Slot& b = slots_[size_t(s.follower)];
    std::vector<double> tb;
    s.t = discretizeShared(s, b, &tb);
    const int bFirst = b.gid.front(), bLast = b.gid.back();
    b.gid.clear();
    std::vector<int> inner;
    for (size_t i = 1; i + 1 < s.t.size(); ++i) inner.push_back(nextId_ + int(i) - 1);
    std::vector<double> bt = tb;
    std::vector<int> bid{b.masterReversed ? bLast : bFirst};
    bid.insert(bid.end(), inner.begin(), inner.end());
    bid.push_back(b.masterReversed ? bFirst : bLast);
    if (b.masterReversed) {
      std::reverse(bt.begin(), bt.end());
      std::reverse(bid.begin(), bid.end());
    }
    // b's ends keep their own corner ids (same corners by construction).
    bid.front() = bFirst, bid.back() = bLast;
    b.t = bt;
    b.gid = bid;
    b.invalid = false;
  }
  for (size_t i = 1; i + 1 < s.t.size(); ++i) gid.push_back(nextId_++);
  gid.push_back(last);
  s.gid = gid;
  s.invalid = false;
}

std::vector<BoundaryLoop> ModelMesher::loopsOf(int p, std::vector<int>* ids, std::vector<char>* sharedEdge,
                                               bool edgeMidpoints) const {
  const SurfacePatch& patch = m_.patches[size_t(p)];
  std::vector<BoundaryLoop> loops;
  for (int k = 0; k < contourCount(patch); ++k) {
    const Contour& c = contourOf(patch, k);
    BoundaryLoop loop;
    std::vector<int> lid;
    std::vector<char> lsh;
    for (size_t j = 0; j < c.curves.size(); ++j) {
      const Slot& s = slots_[size_t(ps_[size_t(p)].slots[size_t(k)][j])];
      const bool rev = c.curves[j].reversed;
      const size_t n = s.t.size();
      for (size_t i = 0; i + 1 < n; ++i) {
        const size_t q = rev ? n - 1 - i : i;
        loop.points.push_back(uvOf(s, q));
        lid.push_back(s.gid[q]);
        loop.edgeRefs.push_back(s.c->ref());
        lsh.push_back(s.master >= 0 || s.follower >= 0);
        if (edgeMidpoints) loop.edgeMidpoints.push_back(s.c->point(0.5 * (s.t[q] + s.t[rev ? q - 1 : q + 1])));
      }
    }
    const bool ccw = signedArea(loop.points) > 0;
    if (ccw != (k == 0)) {
      const size_t n = loop.points.size();
      BoundaryLoop rev;
      std::vector<int> rid;
      std::vector<char> rsh;
      for (size_t i = 0; i < n; ++i) {
        rev.points.push_back(loop.points[n - 1 - i]);
        rid.push_back(lid[n - 1 - i]);
        const size_t e = (2 * n - 2 - i) % n;
        rev.edgeRefs.push_back(loop.edgeRefs[e]);
        rsh.push_back(lsh[e]);
        if (edgeMidpoints) rev.edgeMidpoints.push_back(loop.edgeMidpoints[e]);
      }
      loop = std::move(rev);
      lid = std::move(rid);
      lsh = std::move(rsh);
    }
    if (ids) ids->insert(ids->end(), lid.begin(), lid.end());
    if (sharedEdge) sharedEdge->insert(sharedEdge->end(), lsh.begin(), lsh.end());
    loops.push_back(std::move(loop));
  }
  return loops;
}

// Each patch takes its neighbour's metric at the shared points, converted through the
// Jacobians (neighbour (u, v) -> 3D tangent metric -> own (u, v)), as node sources.
void ModelMesher::adaptAcrossShared() {
  for (const Slot& a : slots_) {
    if (a.follower < 0) continue;
    const Slot& b = slots_[size_t(a.follower)];
    const Surface& sa = *m_.patches[size_t(a.patch)].surface;
    const Surface& sb = *m_.patches[size_t(b.patch)].surface;
    NodeSource toA, toB;
    const size_t n = a.t.size();
    for (size_t i = 0; i < n; ++i) {
      const size_t ib = b.masterReversed ? n - 1 - i : i;
      const Vec2 ua = uvOf(a, i), ub = uvOf(b, ib);
      const SurfaceDerivatives da = sa.derivatives(ua), db = sb.derivatives(ub);
      if (isDegenerate(da) || isDegenerate(db)) continue;
      const Mat3 ma = metric3DFromParameter(space(a.patch).metricAt(ua), da);
      const Mat3 mb = metric3DFromParameter(space(b.patch).metricAt(ub), db);
      toA.points.push_back(ua);
      toA.metrics.push_back(pullBackMetric(mb, da));
      toB.points.push_back(ub);
      toB.metrics.push_back(pullBackMetric(ma, db));
    }
    if (!toA.points.empty()) addSource(a.patch, toA);
    if (!toB.points.empty()) addSource(b.patch, toB);
  }
}

}  // namespace surface_mesher

}  // namespace anisomesh

// Section 4.3: Mt and Mp apart in the control nodes of a patch's control space.
#include "anisomesh/controlspace/parameterized_control_space.h"

#include <cmath>

#include "anisomesh/core/error.h"

namespace anisomesh {

namespace {

Mat2 matOf(const SymMt& s) {
  Mat2 m;
  m << s.a, s.b, s.b, s.c;
  return m;
}

// sum_k w_k field[n_k] over a stencil.
SymMt interpolate(const std::vector<SymMt>& field, const InterpolationStencil& s) {
  SymMt r{0.0, 0.0, 0.0};
  for (int k = 0; k < s.count; ++k) {
    const SymMt& m = field[size_t(s.nodes[size_t(k)])];
    const double w = s.weights[size_t(k)];
    r.a += w * m.a;
    r.b += w * m.b;
    r.c += w * m.c;
  }
  return r;
}

// Mt = sqrt(Mp^-1 M Mp^-1) of a node; false when Mp is unusable there.
bool splitNode(const Mat2& m, const Mat2& mp, SymMt& tangent) {
  if (!mp.allFinite()) return false;
  const double det = mp.determinant(), tr = mp.trace();
  if (!(det > 1e-12 * tr * tr) || !(tr > 0)) return false;
  const Mat2 inv = mp.inverse();
  Mat2 t = inv * m * inv;
  t(0, 1) = t(1, 0) = 0.5 * (t(0, 1) + t(1, 0));
  const Mat2 mt = sqrtSpd(t);
  if (!mt.allFinite()) return false;
  tangent = SymMt::from(mt);
  return true;
}

}  // namespace

ParameterizedControlSpace::ParameterizedControlSpace(const AdaptiveControlSpace& space, ParameterizationFunction mp,
                                                     ParameterizationStorage storage)
    : space_(space), mp_(std::move(mp)), storage_(storage) {
  require(storage == ParameterizationStorage::Stored || storage == ParameterizationStorage::Computed,
          ErrorCode::InvalidArgument, "a parameterized control space stores Mp or computes it");
  require(static_cast<bool>(mp_), ErrorCode::InvalidArgument, "a parameterized control space needs Mp");
  const int n = space.nodeCount();
  tangent_.resize(size_t(n));
  param_.resize(size_t(n));
  for (int i = 0; i < n; ++i) {
    if (!space.nodeIsFree(i)) continue;  // from the masters, below
    const Mat2 m = space.nodeMetric(i).tensor();
    Mat2 p;
    bool ok = true;
    try {
      p = mp_(space.nodePosition(i));
    } catch (const Error&) {
      ok = false;
    }
    if (ok && splitNode(m, p, tangent_[size_t(i)])) {
      param_[size_t(i)] = SymMt::from(p);
    } else {  // no usable Mp here: the node keeps M (Mt = sqrt M, Mp = I)
      tangent_[size_t(i)] = space.nodeMt(i);
      param_[size_t(i)] = SymMt{};
    }
  }
  for (const auto& h : space.hangingNodes()) {
    SymMt t{0.0, 0.0, 0.0}, q{0.0, 0.0, 0.0};
    for (size_t k = 0; k < 3; ++k) {
      const double w = h.weights[k];
      if (w == 0.0) continue;
      const SymMt& tm = tangent_[size_t(h.masters[k])];
      const SymMt& pm = param_[size_t(h.masters[k])];
      t.a += w * tm.a, t.b += w * tm.b, t.c += w * tm.c;
      q.a += w * pm.a, q.b += w * pm.b, q.c += w * pm.c;
    }
    tangent_[size_t(h.node)] = t;
    param_[size_t(h.node)] = q;
  }
}

Mat2 ParameterizedControlSpace::parameterizationAt(const Vec2& p) const {
  if (storage_ == ParameterizationStorage::Computed) return mp_(p);
  return matOf(interpolate(param_, space_.stencilAt(p)));
}

Metric ParameterizedControlSpace::metricAt(const Vec2& p) const {
  const InterpolationStencil s = space_.stencilAt(p);
  const Mat2 t = matOf(interpolate(tangent_, s));
  Mat2 mp;
  if (storage_ == ParameterizationStorage::Computed) {
    bool ok = true;
    try {
      mp = mp_(p);
    } catch (const Error&) {
      ok = false;
    }
    // A degenerate point of the parameterization: the nodes' Mp instead.
    if (!ok || !mp.allFinite() || !(mp.determinant() > 0)) mp = matOf(interpolate(param_, s));
  } else {
    mp = matOf(interpolate(param_, s));
  }
  Mat2 m = mp * t * t * mp;
  m(0, 1) = m(1, 0) = 0.5 * (m(0, 1) + m(1, 0));
  return Metric::fromTransformUnchecked(sqrtSpd(m));
}

}  // namespace anisomesh

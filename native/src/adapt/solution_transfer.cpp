#include "anisomesh/adapt/solution_transfer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "anisomesh/adapt/hessian_recovery.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/int_conversion.h"

namespace anisomesh {

TriangleLocator::TriangleLocator(const Mesh& mesh) : tris_(meshTriangles(mesh)) {
  require(!tris_.empty(), ErrorCode::InvalidArgument, "point location: the mesh has no triangles");
  for (const Vec3& p : mesh.points) pts_.push_back(p.head<2>());
  Vec2 lo = pts_[size_t(tris_[0][0])], hi = lo;
  for (const auto& t : tris_)
    for (int v : t) lo = lo.cwiseMin(pts_[size_t(v)]), hi = hi.cwiseMax(pts_[size_t(v)]);
  lo_ = lo;
  const Vec2 size = (hi - lo).cwiseMax(Vec2::Constant(1e-300));
  const double side = std::sqrt(size.x() * size.y() / double(tris_.size()));
  nx_ = std::max(1, std::min(4096, side > 0 ? int(size.x() / side) : 1));
  ny_ = std::max(1, std::min(4096, side > 0 ? int(size.y() / side) : 1));
  cell_ = Vec2(size.x() / nx_, size.y() / ny_);
  auto range = [&](const std::array<int, 3>& t, int r[4]) {
    Vec2 a = pts_[size_t(t[0])], b = a;
    for (int v : t) a = a.cwiseMin(pts_[size_t(v)]), b = b.cwiseMax(pts_[size_t(v)]);
    r[0] = std::min(nx_ - 1, std::max(0, int((a.x() - lo_.x()) / cell_.x())));
    r[1] = std::min(nx_ - 1, std::max(0, int((b.x() - lo_.x()) / cell_.x())));
    r[2] = std::min(ny_ - 1, std::max(0, int((a.y() - lo_.y()) / cell_.y())));
    r[3] = std::min(ny_ - 1, std::max(0, int((b.y() - lo_.y()) / cell_.y())));
  };
  cellStart_.assign(size_t(nx_) * size_t(ny_) + 1, 0);
  int r[4];
  for (const auto& t : tris_) {
    range(t, r);
    for (int y = r[2]; y <= r[3]; ++y)
      for (int x = r[0]; x <= r[1]; ++x) ++cellStart_[size_t(cellIndex(x, y)) + 1];
  }
  for (size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
  cellTris_.resize(size_t(cellStart_.back()));
  std::vector<int> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (int i = 0; i < int(tris_.size()); ++i) {
    range(tris_[size_t(i)], r);
    for (int y = r[2]; y <= r[3]; ++y)
      for (int x = r[0]; x <= r[1]; ++x) cellTris_[size_t(fill[size_t(cellIndex(x, y))]++)] = i;
  }
}

int TriangleLocator::locate(const Vec2& p, std::array<double, 3>* bary, bool* inside) const {
  const int cx = clampedCell((p.x() - lo_.x()) / cell_.x(), nx_);
  const int cy = clampedCell((p.y() - lo_.y()) / cell_.y(), ny_);
  auto coords = [&](int t, const Vec2& q, double l[3]) {
    const auto& tri = tris_[size_t(t)];
    const Vec2 &a = pts_[size_t(tri[0])], &b = pts_[size_t(tri[1])], &c = pts_[size_t(tri[2])];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    l[1] = ((q.x() - a.x()) * (c.y() - a.y()) - (q.y() - a.y()) * (c.x() - a.x())) / det;
    l[2] = ((b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x())) / det;
    l[0] = 1.0 - l[1] - l[2];
    return det != 0;
  };
  int best = -1, foundRing = -1;
  double bestDist = INFINITY;
  Vec2 bestPoint = p;
  for (int ring = 0; ring <= std::max(nx_, ny_); ++ring) {
    for (int y = cy - ring; y <= cy + ring; ++y)
      for (int x = cx - ring; x <= cx + ring; ++x) {
        if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
        if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring) continue;
        const int c = cellIndex(x, y);
        for (int k = cellStart_[size_t(c)]; k < cellStart_[size_t(c) + 1]; ++k) {
          const int t = cellTris_[size_t(k)];
          double l[3];
          if (!coords(t, p, l)) continue;
          if (l[0] >= -1e-12 && l[1] >= -1e-12 && l[2] >= -1e-12) {
            const double lc[3] = {std::max(l[0], 0.0), std::max(l[1], 0.0), std::max(l[2], 0.0)};
            const double sum = lc[0] + lc[1] + lc[2];
            *bary = {lc[0] / sum, lc[1] / sum, lc[2] / sum};
            if (inside) *inside = true;
            return t;
          }
          const auto& tri = tris_[size_t(t)];
          for (int e = 0; e < 3; ++e) {
            const Vec2 &a = pts_[size_t(tri[e])], &b = pts_[size_t(tri[(e + 1) % 3])];
            const Vec2 ab = b - a;
            const double len2 = ab.squaredNorm();
            const double s = len2 > 0 ? std::min(1.0, std::max(0.0, (p - a).dot(ab) / len2)) : 0.0;
            const Vec2 q = a + s * ab;
            const double dist = (q - p).squaredNorm();
            if (dist < bestDist) bestDist = dist, best = t, bestPoint = q;
          }
        }
      }
    if (best >= 0 && foundRing < 0) foundRing = ring;
    if (foundRing >= 0 && ring >= foundRing + 1) break;
  }
  require(best >= 0, ErrorCode::InvalidArgument, "point location: every triangle of the mesh is degenerate");
  double l[3];
  coords(best, bestPoint, l);
  const double lc[3] = {std::max(l[0], 0.0), std::max(l[1], 0.0), std::max(l[2], 0.0)};
  const double sum = lc[0] + lc[1] + lc[2];
  *bary = {lc[0] / sum, lc[1] / sum, lc[2] / sum};
  if (inside) *inside = false;
  return best;
}

std::vector<std::vector<double>> transferFields(const Mesh& from, const std::vector<std::vector<double>>& fields,
                                                const Mesh& to) {
  for (const auto& f : fields) validateField(from, f);
  const TriangleLocator locator(from);
  std::vector<std::vector<double>> out(fields.size(), std::vector<double>(to.points.size()));
  for (size_t i = 0; i < to.points.size(); ++i) {
    std::array<double, 3> l;
    const auto& tri = locator.triangle(locator.locate(to.points[i].head<2>(), &l));
    for (size_t f = 0; f < fields.size(); ++f)
      out[f][i] =
          l[0] * fields[f][size_t(tri[0])] + l[1] * fields[f][size_t(tri[1])] + l[2] * fields[f][size_t(tri[2])];
  }
  return out;
}

}  // namespace anisomesh

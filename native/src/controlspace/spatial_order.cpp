// The Z-order in which the refinement evaluates independent queries.
#include "spatial_order.h"

#include <algorithm>
#include <cstdint>

namespace anisomesh {
namespace controlspace_internal {
namespace {

// The bits of v (< 2^16) spread to the even bits of the result.
std::uint32_t spreadBits(std::uint32_t v) {
  v = (v | v << 8) & 0x00FF00FFu;
  v = (v | v << 4) & 0x0F0F0F0Fu;
  v = (v | v << 2) & 0x33333333u;
  return (v | v << 1) & 0x55555555u;
}

// v's position in [lo, lo + ext] on 16 bits (a non-finite value or extent gives 0).
std::uint32_t quantized(double v, double lo, double ext) {
  const double t = (v - lo) / ext * 65535.0;
  return t >= 0.0 && t <= 65535.0 ? std::uint32_t(t) : 0u;
}

}  // namespace

std::vector<int> zOrder(const std::vector<Vec2>& points) {
  std::vector<int> order(points.size());
  if (points.empty()) return order;
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2 ext = (hi - lo).cwiseMax(Vec2::Constant(1e-300));
  // Morton keys sorted by a stable radix sort (three 11-bit digits): the ties keep the
  // index order. A Hilbert key keeps neighbours a little closer but costs 10 times more
  // to compute; the 1e6 remeshing runs were no faster with it.
  const size_t n = points.size();
  std::vector<std::uint32_t> key(n);
  for (size_t i = 0; i < n; ++i)
    key[i] = spreadBits(quantized(points[i].x(), lo.x(), ext.x())) |
             spreadBits(quantized(points[i].y(), lo.y(), ext.y())) << 1;
  std::vector<int> from(n);
  for (size_t i = 0; i < n; ++i) from[i] = static_cast<int>(i);
  for (int shift = 0; shift < 32; shift += 11) {
    std::vector<int> count(2049, 0);
    for (size_t k = 0; k < n; ++k) ++count[(key[size_t(from[k])] >> shift & 2047u) + 1];
    for (int d = 0; d < 2048; ++d) count[d + 1] += count[d];
    for (size_t k = 0; k < n; ++k) order[size_t(count[key[size_t(from[k])] >> shift & 2047u]++)] = from[k];
    order.swap(from);
  }
  order.swap(from);
  return order;
}

}  // namespace controlspace_internal
}  // namespace anisomesh

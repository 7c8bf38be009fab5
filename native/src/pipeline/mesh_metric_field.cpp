#include "anisomesh/pipeline/mesh_metric_field.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/core/int_conversion.h"
#include "anisomesh/core/parallel.h"

namespace anisomesh {
namespace {

// Triangles per grid cell: coarser cells list each (thin) triangle in fewer cells, finer
// ones test fewer triangles per query (the sub-cell filter refuses most of them unread).
// The lists' memory only matters on large carriers: 1 per cell up to 2^18 triangles,
// growing to 16 at 2^22 and more (the 1e6 front of native/bench/remesh_throughput.mjs, a
// 4M-triangle carrier: its remesh peaks at 237.6 MiB with 16, 253 with 8, 340 with 1, for
// the same control-space time within the noise; its 2,000-triangle case on 80k is fastest
// with 1). The answers do not depend on it (metricAt's search is exact).
double trianglesPerCell(size_t triangles) { return std::min(16.0, std::max(1.0, double(triangles) / 262144.0)); }

// Each list entry's filter: its triangle's widened box in a kFilterSide^2 grid of the cell.
constexpr int kFilterSide = 16;
// Kept triangles whose points metricAt requests from memory together before testing them.
constexpr int kTestBatch = 8;

// The four filters packed in a word (the first in the low bits) are read with one load:
// the packing is the memory order of little-endian targets (x86-64, WebAssembly).
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the filters are read four at a time");

// The query word of sub-cell (sx, sy) for filtersKeep: its bytes sx, sy, sx, sy, ...
std::uint64_t filterQuery(unsigned sx, unsigned sy) { return std::uint64_t(sx | sy << 8) * 0x0001000100010001ull; }

// Of the four filters in w, those that keep the sub-cell of query q: bit 16 j + 7 set for
// filter j. Without branches (a branch per filter, mispredicted at random, cost more than
// the test): the nibbles are spread into bytes (x0, y0 and x1, y1 of each filter), whose
// spare high bit lets one subtraction compare eight of them without borrows between them.
std::uint64_t filtersKeep(std::uint64_t w, std::uint64_t q) {
  constexpr std::uint64_t kLow = 0x0F0F0F0F0F0F0F0Full, kHigh = 0x8080808080808080ull;
  const std::uint64_t first = w & kLow, last = w >> 4 & kLow;
  const std::uint64_t ge = ((q | kHigh) - first) & ((last | kHigh) - q) & kHigh;
  return ge & ge >> 8 & 0x0080008000800080ull;
}

// Items per parallel chunk of the index build (fixed: the same index for any thread count).
constexpr size_t kBuildChunk = 65536;

}  // namespace

TriangleMeshMetricField::TriangleMeshMetricField(const Mesh& mesh, const std::vector<Metric>& metrics)
    : metrics_(metrics.data()) {
  require(int(metrics.size()) == mesh.vertexCount(), ErrorCode::InvalidArgument,
          "metric field: " + std::to_string(metrics.size()) + " metrics for " + std::to_string(mesh.vertexCount()) +
              " vertices");
  build(mesh);
}

TriangleMeshMetricField::TriangleMeshMetricField(const Mesh& mesh, std::vector<Metric>&& metrics)
    : ownedMetrics_(std::move(metrics)) {
  require(int(ownedMetrics_.size()) == mesh.vertexCount(), ErrorCode::InvalidArgument,
          "metric field: " + std::to_string(ownedMetrics_.size()) + " metrics for " +
              std::to_string(mesh.vertexCount()) + " vertices");
  metrics_ = ownedMetrics_.data();
  build(mesh);
}

void TriangleMeshMetricField::build(const Mesh& mesh) {
  // In parallel chunks; the lowest chunk's error is rethrown, so the message (formatted
  // only then) names the first such vertex for any thread count.
  parallelChunks(mesh.points.size(), kBuildChunk, [&](size_t, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i)
      if (!mesh.points[i].head<2>().allFinite())
        throw Error(ErrorCode::InvalidDomain,
                    "metric field: vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
  });
  pts_ = mesh.points.data();
  if (mesh.quads.empty()) {
    tris_ = mesh.triangles.data();
    triCount_ = mesh.triangles.size();
  } else {
    splitTris_ = mesh.triangles;
    for (const auto& q : mesh.quads) {
      splitTris_.push_back({q[0], q[1], q[2]});
      splitTris_.push_back({q[0], q[2], q[3]});
    }
    tris_ = splitTris_.data();
    triCount_ = splitTris_.size();
  }
  require(triCount_ > 0, ErrorCode::InvalidArgument, "metric field: the mesh has no triangles or quadrilaterals");
  // The box of the triangles' vertices: one per chunk, combined in chunk order (the
  // coordinates are finite: min and max give the box of the sequential scan).
  std::vector<Box2> chunkBoxes(chunkCount(triCount_, kBuildChunk));
  parallelChunks(triCount_, kBuildChunk, [&](size_t chunk, size_t b, size_t e) {
    Box2 cb;
    cb.lo = cb.hi = point(tris_[b][0]);
    for (size_t t = b; t < e; ++t)
      for (int v : tris_[t]) {
        cb.lo = cb.lo.cwiseMin(point(v));
        cb.hi = cb.hi.cwiseMax(point(v));
      }
    chunkBoxes[chunk] = cb;
  });
  box_ = chunkBoxes[0];
  for (const Box2& cb : chunkBoxes) {
    box_.lo = box_.lo.cwiseMin(cb.lo);
    box_.hi = box_.hi.cwiseMax(cb.hi);
  }
  // Barycentric determinants are products of two spans: they must stay finite.
  const Vec2 span = box_.size();
  require(std::isfinite(4.0 * span.x() * span.y()) && span.allFinite(), ErrorCode::InvalidDomain,
          "metric field: the mesh's coordinates span more than the double range allows");
  // About trianglesPerCell triangles per cell on square-ish cells.
  const Vec2 size = box_.size().cwiseMax(Vec2::Constant(1e-300));
  const double side = std::sqrt(trianglesPerCell(triCount_) * size.x() * size.y() / double(triCount_));
  nx_ = side > 0 ? std::max(1, clampedCell(size.x() / side, 2049)) : 1;
  ny_ = side > 0 ? std::max(1, clampedCell(size.y() / side, 2049)) : 1;
  cell_ = Vec2(size.x() / nx_, size.y() / ny_);
  auto range = [&](const std::array<int, 3>& t, int* x0, int* x1, int* y0, int* y1) {
    Vec2 lo = point(t[0]), hi = point(t[0]);
    for (int v : t) {
      lo = lo.cwiseMin(point(v));
      hi = hi.cwiseMax(point(v));
    }
    *x0 = clampedCell((lo.x() - box_.lo.x()) / cell_.x(), nx_);
    *x1 = clampedCell((hi.x() - box_.lo.x()) / cell_.x(), nx_);
    *y0 = clampedCell((lo.y() - box_.lo.y()) / cell_.y(), ny_);
    *y1 = clampedCell((hi.y() - box_.lo.y()) / cell_.y(), ny_);
  };
  // Each triangle's cell range, computed once in parallel chunks and packed in 32 bits
  // (x0, y0: 12 bits each, nx, ny <= 2049; the widths x1 - x0, y1 - y0: 4 bits each, 15:
  // wider, recomputed from the points). On one thread, the cells' counts come with them
  // (one pass over the triangles less); on several, each counts a band of rows after.
  cellStart_.assign(size_t(nx_) * ny_ + 1, 0);
  const bool countWithRanges = threadCount() == 1;
  std::vector<std::uint32_t> ranges(triCount_);
  parallelChunks(triCount_, kBuildChunk, [&](size_t, size_t b, size_t e) {
    int x0, x1, y0, y1;
    for (size_t t = b; t < e; ++t) {
      range(tris_[t], &x0, &x1, &y0, &y1);
      ranges[t] = std::uint32_t(x0) | std::uint32_t(y0) << 12 | std::uint32_t(std::min(x1 - x0, 15)) << 24 |
                  std::uint32_t(std::min(y1 - y0, 15)) << 28;
      if (countWithRanges)
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) ++cellStart_[cellIndex(x, y) + 1];
    }
  });
  auto unpack = [&](size_t t, int* x0, int* x1, int* y0, int* y1) {
    const std::uint32_t r = ranges[t];
    const int w = int(r >> 24 & 15u), h = int(r >> 28);
    if (w == 15 || h == 15) return range(tris_[t], x0, x1, y0, y1);
    *x0 = int(r & 4095u), *y0 = int(r >> 12 & 4095u);
    *x1 = *x0 + w, *y1 = *y0 + h;
  };
  // Each thread owns a band of cell rows and scans every triangle's range for its rows:
  // the lists (each cell's triangles in increasing order) do not depend on the bands.
  const int bands = std::max(1, std::min(threadCount(), ny_));
  auto perBand = [&](auto&& f) {
    parallelChunks(size_t(bands), 1, [&](size_t band, size_t, size_t) {
      const int r0 = int(std::int64_t(ny_) * std::int64_t(band) / bands);
      const int r1 = int(std::int64_t(ny_) * std::int64_t(band + 1) / bands);
      f(r0, r1);
    });
  };
  if (!countWithRanges)
    perBand([&](int r0, int r1) {
      int x0, x1, y0, y1;
      for (size_t t = 0; t < triCount_; ++t) {
        unpack(t, &x0, &x1, &y0, &y1);
        for (int y = std::max(y0, r0); y <= std::min(y1, r1 - 1); ++y)
          for (int x = x0; x <= x1; ++x) ++cellStart_[cellIndex(x, y) + 1];
      }
    });
  // cellStart_[c + 1] = the end of cell c; filled backwards from the ends (triangles in
  // decreasing order), each ends at its start with the triangles in increasing order.
  for (size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
  cellTris_.resize(size_t(cellStart_.back()));
  cellFilter_.resize(cellTris_.size() + 3);  // (3 more: metricAt reads four from any entry on)
  // A triangle containing p (barycentric coordinates >= -1e-12) lies within 3e-12 of its
  // diameter from p, plus the rounding of the coordinates: the margin is far above both.
  const double extent =
      std::max({std::abs(box_.lo.x()), std::abs(box_.lo.y()), std::abs(box_.hi.x()), std::abs(box_.hi.y())});
  const Vec2 margin = Vec2::Constant(1e-9 * (cell_.x() + cell_.y() + box_.size().norm()) + 1e-12 * extent);
  subScale_ = Vec2(kFilterSide / cell_.x(), kFilterSide / cell_.y());
  perBand([&](int r0, int r1) {
    int x0, x1, y0, y1;
    for (int i = int(triCount_) - 1; i >= 0; --i) {
      unpack(size_t(i), &x0, &x1, &y0, &y1);
      const int ya = std::max(y0, r0), yb = std::min(y1, r1 - 1);
      if (ya > yb) continue;
      const std::array<int, 3>& t = tris_[size_t(i)];
      Vec2 lo = point(t[0]), hi = point(t[0]);
      for (int v : t) {
        lo = lo.cwiseMin(point(v));
        hi = hi.cwiseMax(point(v));
      }
      lo -= margin;
      hi += margin;
      for (int y = ya; y <= yb; ++y) {
        const Vec2 o0 = cellOrigin(x0, y);
        const unsigned fy = unsigned(clampedCell((lo.y() - o0.y()) * subScale_.y(), kFilterSide)) << 8 |
                            unsigned(clampedCell((hi.y() - o0.y()) * subScale_.y(), kFilterSide)) << 12;
        for (int x = x0; x <= x1; ++x) {
          const Vec2 o = cellOrigin(x, y);
          const size_t k = size_t(--cellStart_[cellIndex(x, y) + 1]);
          cellTris_[k] = i;
          cellFilter_[k] = std::uint16_t(fy | unsigned(clampedCell((lo.x() - o.x()) * subScale_.x(), kFilterSide)) |
                                         unsigned(clampedCell((hi.x() - o.x()) * subScale_.x(), kFilterSide)) << 4);
        }
      }
    }
  });
  std::vector<std::uint32_t>().swap(ranges);
  // Now cellStart_[c + 1] is the start of cell c: shifted down by one cell.
  for (size_t c = 0; c + 1 < cellStart_.size(); ++c) cellStart_[c] = cellStart_[c + 1];
  cellStart_.back() = int(cellTris_.size());
  coveredSum_.assign(size_t(nx_ + 1) * (ny_ + 1), 0);
  for (int y = 0; y < ny_; ++y)
    for (int x = 0; x < nx_; ++x) {
      const int c = cellIndex(x, y);
      coveredSum_[size_t(y + 1) * (nx_ + 1) + x + 1] =
          (cellStart_[c + 1] > cellStart_[c] ? 1 : 0) + coveredSum_[size_t(y) * (nx_ + 1) + x + 1] +
          coveredSum_[size_t(y + 1) * (nx_ + 1) + x] - coveredSum_[size_t(y) * (nx_ + 1) + x];
    }
  // Chebyshev distance (in cells) from each cell to the nearest cell holding a triangle:
  // two chamfer passes with unit weights over the 8 neighbours are exact for it.
  const int far = nx_ + ny_;  // <= 4098: fits the 16-bit entries
  emptyRings_.assign(size_t(nx_) * ny_, far);
  for (int c = 0; c < nx_ * ny_; ++c)
    if (cellStart_[c + 1] > cellStart_[c]) emptyRings_[size_t(c)] = 0;
  auto relax = [&](int x, int y, int dx, int dy) {
    const int nxp = x + dx, nyp = y + dy;
    if (nxp < 0 || nyp < 0 || nxp >= nx_ || nyp >= ny_) return;
    std::uint16_t& d = emptyRings_[size_t(cellIndex(x, y))];
    d = std::min<std::uint16_t>(d, std::uint16_t(emptyRings_[size_t(cellIndex(nxp, nyp))] + 1));
  };
  for (int y = 0; y < ny_; ++y)
    for (int x = 0; x < nx_; ++x) {
      relax(x, y, -1, 0), relax(x, y, -1, -1), relax(x, y, 0, -1), relax(x, y, 1, -1);
    }
  for (int y = ny_ - 1; y >= 0; --y)
    for (int x = nx_ - 1; x >= 0; --x) {
      relax(x, y, 1, 0), relax(x, y, 1, 1), relax(x, y, 0, 1), relax(x, y, -1, 1);
    }
}

bool TriangleMeshMetricField::meets(const Box2& b) const {
  auto cell = [](double v, double lo, double size, int n) { return clampedCell((v - lo) / size, n); };
  if (!(b.lo.allFinite() && b.hi.allFinite())) return true;
  const int x0 = cell(b.lo.x(), box_.lo.x(), cell_.x(), nx_), x1 = cell(b.hi.x(), box_.lo.x(), cell_.x(), nx_);
  const int y0 = cell(b.lo.y(), box_.lo.y(), cell_.y(), ny_), y1 = cell(b.hi.y(), box_.lo.y(), cell_.y(), ny_);
  auto sum = [&](int x, int y) { return coveredSum_[size_t(y) * (nx_ + 1) + x]; };
  return sum(x1 + 1, y1 + 1) - sum(x0, y1 + 1) - sum(x1 + 1, y0) + sum(x0, y0) > 0;
}

Metric TriangleMeshMetricField::metricAt(const Vec2& p) const {
  if (!p.allFinite()) throw Error(ErrorCode::InvalidArgument, "metric field: the query point is not finite");
  const int cx = clampedCell((p.x() - box_.lo.x()) / cell_.x(), nx_);
  const int cy = clampedCell((p.y() - box_.lo.y()) / cell_.y(), ny_);
  // Interpolates Mt at q, given in triangle t.
  auto interpolateAt = [this](int t, const Vec2& q) {
    const auto& tri = tris_[size_t(t)];
    const Vec2 a = point(tri[0]), b = point(tri[1]), c = point(tri[2]);
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    double l1 = ((q.x() - a.x()) * (c.y() - a.y()) - (q.y() - a.y()) * (c.x() - a.x())) / det;
    double l2 = ((b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x())) / det;
    double l0 = 1.0 - l1 - l2;
    l0 = std::max(l0, 0.0), l1 = std::max(l1, 0.0), l2 = std::max(l2, 0.0);
    const double sum = l0 + l1 + l2;
    const Mat2 mt = (l0 * metrics_[size_t(tri[0])].transform() + l1 * metrics_[size_t(tri[1])].transform() +
                     l2 * metrics_[size_t(tri[2])].transform()) /
                    sum;
    return Metric::fromTransformUnchecked(mt);
  };
  auto closestOnSegment = [](const Vec2& q, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0 ? std::min(1.0, std::max(0.0, (q - a).dot(ab) / l2)) : 0.0;
    return Vec2(a + t * ab);
  };
  int best = -1;
  double bestDist = INFINITY;
  Vec2 bestPoint = p;
  // Cell c's triangles, in two passes per ring of cells: a containing one ends the search
  // (true); only when the ring holds none, the nearest point of each is a candidate (of
  // equal distances the lowest triangle index wins, whatever the visiting order).
  // (the cell of a point is decided by a division: a relative slack on distance bounds)
  const double slack = 1e-9 * (cell_.x() + cell_.y() + box_.size().norm());
  // The distance from p to the box of cell (x, y).
  auto cellDistance = [&](int x, int y) {
    const double x0 = box_.lo.x() + x * cell_.x(), y0 = box_.lo.y() + y * cell_.y();
    const double dx = std::max({0.0, x0 - p.x(), p.x() - (x0 + cell_.x())});
    const double dy = std::max({0.0, y0 - p.y(), p.y() - (y0 + cell_.y())});
    return std::sqrt(dx * dx + dy * dy);
  };
  // A cell farther than the slack holds no triangle containing p that p's own cell (or a
  // nearer one) does not list: skipped.
  auto contains = [&](int t) {
    const auto& tri = tris_[size_t(t)];
    const Vec2 a = point(tri[0]), b = point(tri[1]), d = point(tri[2]);
    const double det = (b.x() - a.x()) * (d.y() - a.y()) - (b.y() - a.y()) * (d.x() - a.x());
    if (det == 0) return false;
    const double n1 = (p.x() - a.x()) * (d.y() - a.y()) - (p.y() - a.y()) * (d.x() - a.x());
    const double n2 = (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
    // Most triangles are refused without the divisions: n / det below -2e-12 (its rounded
    // quotient is then below -1e-12 too; a tiny det could make the bound lose its precision).
    const double scale = std::abs(det);
    if (scale > 1e-280) {
      const double bound = -2e-12 * scale;
      if ((det > 0 ? n1 : -n1) < bound || (det > 0 ? n2 : -n2) < bound) return false;
    }
    const double l1 = n1 / det, l2 = n2 / det;
    return l1 >= -1e-12 && l2 >= -1e-12 && 1.0 - l1 - l2 >= -1e-12;
  };
  // (the triangles whose widened box misses p's sub-cell are skipped: they cannot contain
  // p. The filters are tested four at a time; the kept triangles in order, by batches
  // whose points are requested together: one wait for memory per batch, not per triangle)
  auto containsIn = [&](int x, int y) {
    if (cellDistance(x, y) > slack) return false;
    const int c = cellIndex(x, y);
    const Vec2 o = cellOrigin(x, y);
    const std::uint64_t q = filterQuery(unsigned(clampedCell((p.x() - o.x()) * subScale_.x(), kFilterSide)),
                                        unsigned(clampedCell((p.y() - o.y()) * subScale_.y(), kFilterSide)));
    int batch[kTestBatch];
    int n = 0;
    auto testBatch = [&] {
      for (int i = 0; i < n; ++i)
        for (int v : tris_[size_t(batch[i])]) __builtin_prefetch(&pts_[v]);
      for (int i = 0; i < n; ++i)
        if (contains(batch[i])) {
          best = batch[i];
          return true;
        }
      n = 0;
      return false;
    };
    const int end = cellStart_[c + 1];
    for (int k = cellStart_[c]; k < end; k += 4) {
      std::uint64_t w;
      std::memcpy(&w, &cellFilter_[size_t(k)], sizeof w);
      for (std::uint64_t keep = filtersKeep(w, q); keep != 0; keep &= keep - 1) {
        const int at = k + (__builtin_ctzll(keep) >> 4);
        if (at >= end) break;  // (the next cell's, or the padding)
        batch[n++] = cellTris_[size_t(at)];
        if (n == kTestBatch && testBatch()) return true;
      }
    }
    return testBatch();
  };
  // A cell farther than the nearest point found cannot improve it (a triangle's nearest
  // point lies in a cell it is listed in, never farther than the point): skipped.
  auto nearestIn = [&](int x, int y) {
    if (best >= 0 && cellDistance(x, y) - slack > std::sqrt(bestDist)) return false;
    const int c = cellIndex(x, y);
    for (int k = cellStart_[c]; k < cellStart_[c + 1]; ++k) {
      const int t = cellTris_[size_t(k)];
      const auto& tri = tris_[size_t(t)];
      const Vec2 a = point(tri[0]), b = point(tri[1]), d = point(tri[2]);
      const double det = (b.x() - a.x()) * (d.y() - a.y()) - (b.y() - a.y()) * (d.x() - a.x());
      if (det == 0) continue;
      if (best >= 0) {  // a triangle whose box is farther than the nearest point found: skipped
        const double dx =
            std::max({0.0, std::min({a.x(), b.x(), d.x()}) - p.x(), p.x() - std::max({a.x(), b.x(), d.x()})});
        const double dy =
            std::max({0.0, std::min({a.y(), b.y(), d.y()}) - p.y(), p.y() - std::max({a.y(), b.y(), d.y()})});
        if (std::sqrt(dx * dx + dy * dy) - slack > std::sqrt(bestDist)) continue;
      }
      for (int e = 0; e < 3; ++e) {
        const Vec2 q = closestOnSegment(p, point(tri[e]), point(tri[(e + 1) % 3]));
        const double dist = (q - p).squaredNorm();
        // (inf when p is far: the first candidate is taken; a triangle's own first edge of
        // equal distances is kept)
        if (best < 0 || dist < bestDist || (dist == bestDist && t < best)) bestDist = dist, best = t, bestPoint = q;
      }
    }
    return false;
  };
  // The number of cells holding a triangle in columns x0..x1 of rows y0..y1 (in the grid).
  auto covered = [&](int x0, int y0, int x1, int y1) {
    auto sum = [&](int x, int y) { return coveredSum_[size_t(y) * (nx_ + 1) + x]; };
    return sum(x1 + 1, y1 + 1) - sum(x0, y1 + 1) - sum(x1 + 1, y0) + sum(x0, y0);
  };
  // Calls f on the cells of ring r around p's cell in row order; true when f ends the search.
  // (Cells holding no triangle give f nothing: skipped, the ring's sides at once when the
  // summed-area table finds them empty; far from the mesh, most of a ring is empty.)
  auto ring = [&](int r, auto&& f) {
    auto visit = [&](int x, int y) {
      const int c = cellIndex(x, y);
      return cellStart_[c + 1] > cellStart_[c] && f(x, y);
    };
    const int xa = std::max(cx - r, 0), xb = std::min(cx + r, nx_ - 1);
    const int ya = std::max(cy - r + 1, 0), yb = std::min(cy + r - 1, ny_ - 1);
    auto row = [&](int y) {
      if (y < 0 || y >= ny_ || xa > xb || covered(xa, y, xb, y) == 0) return false;
      for (int x = xa; x <= xb; ++x)
        if (visit(x, y)) return true;
      return false;
    };
    if (row(cy - r)) return true;
    const bool left = cx - r >= 0 && ya <= yb && covered(cx - r, ya, cx - r, yb) > 0;
    const bool right = r > 0 && cx + r < nx_ && ya <= yb && covered(cx + r, ya, cx + r, yb) > 0;
    if (left || right)
      for (int y = ya; y <= yb; ++y) {
        if (left && visit(cx - r, y)) return true;
        if (right && visit(cx + r, y)) return true;
      }
    return r > 0 && row(cy + r);
  };
  // A lower bound of the distance from p to the cells of ring r (r >= 1): each of its
  // cells lies in one of its four sides beyond the block of the inner rings; infinite
  // when the ring has no cell in the grid (nor has any further ring).
  auto ringDistance = [&](int r) {
    double d = INFINITY;
    if (cx - r >= 0) d = std::min(d, std::max(0.0, p.x() - (box_.lo.x() + (cx - r + 1) * cell_.x())));
    if (cx + r < nx_) d = std::min(d, std::max(0.0, box_.lo.x() + (cx + r) * cell_.x() - p.x()));
    if (cy - r >= 0) d = std::min(d, std::max(0.0, p.y() - (box_.lo.y() + (cy - r + 1) * cell_.y())));
    if (cy + r < ny_) d = std::min(d, std::max(0.0, box_.lo.y() + (cy + r) * cell_.y() - p.y()));
    return d;
  };
  // Rings of cells around p's cell: a containing triangle ends the search; otherwise the
  // nearest triangle of all: the rings are searched until the next one is farther than
  // the nearest point found (each triangle's nearest point lies in a cell it is listed in),
  // so the answer does not depend on the cell size. Rings closer than the nearest
  // nonempty cell hold nothing: skipped.
  for (int r = emptyRings_[size_t(cellIndex(cx, cy))];; ++r) {
    if (ring(r, containsIn)) return interpolateAt(best, p);
    ring(r, nearestIn);
    const double next = ringDistance(r + 1);
    if (next == INFINITY) break;
    if (best >= 0 && next - slack > std::sqrt(bestDist)) break;
  }
  if (best < 0) throw Error(ErrorCode::InvalidArgument, "metric field: every triangle of the mesh is degenerate");
  return interpolateAt(best, bestPoint);
}

}  // namespace anisomesh

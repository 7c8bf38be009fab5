// Planar mesher: metric area of the domain (the element estimate of the budget check).
#include "mesher_impl.h"

namespace anisomesh {
namespace planar {

// Integral of det(Mt) over the domain (metric area), adaptive over the boundary triangles.
double Mesher::metricAreaRec(const Vec2& a, const Vec2& b, const Vec2& c, double da, double db, double dc, int depth,
                             std::int64_t& budget, int& hint) const {
  const double area = 0.5 * std::fabs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  const Vec2 g = (a + b + c) / 3.0;
  const double dg = cs_.metricAtNear(g, hint).transform().determinant();
  --budget;
  const double lo = std::min({da, db, dc, dg}), hi = std::max({da, db, dc, dg});
  if (depth >= 14 || budget <= 0 || hi <= 1.2 * lo) return area * dg;  // centroid rule
  const Vec2 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  const double dab = cs_.metricAtNear(ab, hint).transform().determinant();
  const double dbc = cs_.metricAtNear(bc, hint).transform().determinant();
  const double dca = cs_.metricAtNear(ca, hint).transform().determinant();
  budget -= 3;
  return metricAreaRec(a, ab, ca, da, dab, dca, depth + 1, budget, hint) +
         metricAreaRec(ab, b, bc, dab, db, dbc, depth + 1, budget, hint) +
         metricAreaRec(ca, bc, c, dca, dbc, dc, depth + 1, budget, hint) +
         metricAreaRec(ab, bc, ca, dab, dbc, dca, depth + 1, budget, hint);
}

// Metric area of the domain, the larger of two estimates: adaptive quadrature over the
// boundary triangles (resolves metric features that touch the boundary) and a scanline
// sampling on a grid of up to `maxRows` rows with even-odd coverage (sees features inside
// the domain that no boundary triangle vertex samples). `subdivisions` bounds the
// quadrature's queries.
double Mesher::metricAreaEstimate(std::int64_t subdivisions, int maxRows) const {
  std::int64_t budget = subdivisions;
  // Each query's location starts where the last one ended (metricAtNear: the same values
  // as metricAt, whose grid search cost 5 % of the meshing stage here).
  int hint = -1;
  double adaptive = 0.0;
  for (const auto& tr : tri_) {
    const auto& t = tr.v;
    const Vec2 &a = vx_[t[0]].p, &b = vx_[t[1]].p, &c = vx_[t[2]].p;
    adaptive += metricAreaRec(a, b, c, vx_[t[0]].m.det(), vx_[t[1]].m.det(), vx_[t[2]].m.det(), 0, budget, hint);
  }
  Vec2 lo = vx_[kSuper].p, hi = lo;
  for (int v = kSuper; v < kSuper + nBoundary_; ++v) {
    lo = lo.cwiseMin(vx_[v].p);
    hi = hi.cwiseMax(vx_[v].p);
  }
  // As many rows as boundary points (64..maxRows): the sampling stays cheap next to the mesh.
  const int rows = std::min(maxRows, std::max(64, nBoundary_));
  const double dy = (hi.y() - lo.y()) / rows, dx = (hi.x() - lo.x()) / rows;
  if (!(dx > 0.0) || !(dy > 0.0)) return adaptive;
  auto rowY = [&](int r) { return lo.y() + (r + 0.5) * dy; };
  // The rows each boundary edge crosses, listed per row in edge order (what a scan of
  // every edge for each row finds, without that scan's rows x edges tests): a contiguous
  // range, as rowY increases with r, entered from a row or two below its first.
  auto forCrossedRows = [&](const std::array<int, 2>& e, auto&& f) {
    const double py = vx_[e[0]].p.y(), qy = vx_[e[1]].p.y();
    const double r0 = std::floor((std::min(py, qy) - lo.y()) / dy - 0.5) - 1.0;
    for (int r = r0 > 0.0 ? static_cast<int>(std::min(r0, static_cast<double>(rows))) : 0; r < rows; ++r) {
      const double y = rowY(r);
      if ((py > y) != (qy > y)) {
        f(r);
      } else if (!(py > y)) {
        break;  // both ends at or below the row: so for every later row
      }
    }
  };
  std::vector<int> rowStart(static_cast<size_t>(rows) + 1, 0), crossing;
  for (const auto& e : bedges_) forCrossedRows(e, [&](int r) { ++rowStart[r + 1]; });
  for (int r = 0; r < rows; ++r) rowStart[r + 1] += rowStart[r];
  crossing.resize(static_cast<size_t>(rowStart[rows]));
  {
    std::vector<int> fill(rowStart.begin(), rowStart.end() - 1);
    for (int k = 0; k < static_cast<int>(bedges_.size()); ++k)
      forCrossedRows(bedges_[k], [&](int r) { crossing[fill[r]++] = k; });
  }
  double grid = 0.0;
  std::vector<double> xs;
  for (int r = 0; r < rows; ++r) {
    const double y = rowY(r);
    xs.clear();
    for (int c = rowStart[r]; c < rowStart[r + 1]; ++c) {
      const auto& e = bedges_[crossing[c]];
      const Vec2 &p = vx_[e[0]].p, &q = vx_[e[1]].p;
      xs.push_back(p.x() + (y - p.y()) / (q.y() - p.y()) * (q.x() - p.x()));
    }
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {
      const double xa = xs[k], xb = xs[k + 1];
      int j = std::max(0, static_cast<int>((xa - lo.x()) / dx));
      for (; j < rows; ++j) {
        const double c0 = std::max(xa, lo.x() + j * dx), c1 = std::min(xb, lo.x() + (j + 1) * dx);
        if (c0 >= xb) break;
        if (c1 <= c0) continue;
        grid += (c1 - c0) * dy * cs_.metricAtNear(Vec2(0.5 * (c0 + c1), y), hint).transform().determinant();
      }
    }
  }
  return std::max(adaptive, grid);
}

double Mesher::estimateMetricArea() {
  // A coarse estimate first (2,000 subdivisions, 64 rows: up to ~6,000 queries). A small
  // mesh keeps it: the fine one cost ~60,000 queries whatever the mesh's size, ten times
  // the mesher's own for a 6,000-triangle surface patch being dragged. Near a decision (the
  // element budget, the domain decomposition's threshold) or above kCoarseEstimateLimit the
  // fine estimate decides, as it always did: 20,000 subdivisions (the first boundary
  // triangles, where the metric varies, take them all whatever the budget; a larger one
  // moved the estimate by under 1 %) and up to 256 rows. The estimate sizes reservations and
  // the progress fractions and guards the budget; the mesh does not depend on it.
  const double coarseArea = metricAreaEstimate(2000, 64);
  const double coarse = trianglesOfMetricArea(coarseArea) * elementRatio_;
  const bool nearBudget = 2.0 * coarse >= static_cast<double>(opt_.maxElements);
  const bool nearParts = opt_.partElements > 0 && coarse >= static_cast<double>(opt_.partElements);
  if (coarse < kCoarseEstimateLimit && !nearBudget && !nearParts) return coarseArea;
  return metricAreaEstimate(20000, 256);
}

}  // namespace planar
}  // namespace anisomesh

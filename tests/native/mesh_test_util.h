#pragma once
// Helpers of the mesh tests: boundary loops, metric-length discretization of straight
// segments, and structural checks of a planar mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/core/error.h"
#include "anisomesh/mesh/planar_mesher.h"
#include "anisomesh/mesh/predicates.h"
#include "anisomesh/mesh/quality.h"

namespace meshtest {

using namespace anisomesh;

inline BoundaryLoop makeLoop(const std::vector<Vec2>& pts, int ref = 1) {
  BoundaryLoop l;
  l.points = pts;
  l.edgeRefs.assign(pts.size(), ref);
  return l;
}

// n points evenly spaced on each side of the polygon through corners (closed).
inline BoundaryLoop polygonLoop(const std::vector<Vec2>& corners, int perSide, int ref = 1) {
  BoundaryLoop l;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec2 a = corners[i], b = corners[(i + 1) % corners.size()];
    for (int k = 0; k < perSide; ++k) {
      l.points.push_back(a + (b - a) * (static_cast<double>(k) / perSide));
      l.edgeRefs.push_back(ref + static_cast<int>(i));
    }
  }
  return l;
}

// Regular n-gon (counter-clockwise unless cw).
inline BoundaryLoop circleLoop(const Vec2& c, double r, int n, bool cw = false, int ref = 10) {
  BoundaryLoop l;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n * (cw ? -1.0 : 1.0);
    l.points.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
    l.edgeRefs.push_back(ref);
  }
  return l;
}

// Points of segment [a, b) spaced at equal metric length, their count the rounded metric
// length of the segment (numerical integration, midpoint rule on 4000 steps).
inline std::vector<Vec2> discretizeSegment(const Vec2& a, const Vec2& b, const ControlSpace& cs) {
  const int steps = 4000;
  std::vector<double> cum(steps + 1, 0.0);
  for (int i = 0; i < steps; ++i) {
    const Vec2 p0 = a + (b - a) * (static_cast<double>(i) / steps);
    const Vec2 p1 = a + (b - a) * (static_cast<double>(i + 1) / steps);
    cum[i + 1] = cum[i] + cs.metricAt(0.5 * (p0 + p1)).length(p1 - p0);
  }
  const double total = cum[steps];
  const int n = std::max(1, static_cast<int>(std::lround(total)));
  std::vector<Vec2> out;
  int j = 0;
  for (int k = 0; k < n; ++k) {
    const double s = total * k / n;
    while (j < steps && cum[j + 1] < s) ++j;
    const double f = cum[j + 1] > cum[j] ? (s - cum[j]) / (cum[j + 1] - cum[j]) : 0.0;
    out.push_back(a + (b - a) * ((j + f) / steps));
  }
  return out;
}

// A closed polygon discretized side by side by metric length.
inline BoundaryLoop metricPolygonLoop(const std::vector<Vec2>& corners, const ControlSpace& cs, int ref = 1) {
  BoundaryLoop l;
  for (size_t i = 0; i < corners.size(); ++i) {
    const auto pts = discretizeSegment(corners[i], corners[(i + 1) % corners.size()], cs);
    for (const auto& p : pts) {
      l.points.push_back(p);
      l.edgeRefs.push_back(ref + static_cast<int>(i));
    }
  }
  return l;
}

inline double loopArea(const BoundaryLoop& l) {
  double a = 0.0;
  const Vec2 o = l.points[0];  // relative coordinates: no cancellation far from the origin
  for (size_t i = 0; i < l.points.size(); ++i) {
    const Vec2 p = l.points[i] - o;
    const Vec2 q = l.points[(i + 1) % l.points.size()] - o;
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * std::fabs(a);
}

inline double domainArea(const std::vector<BoundaryLoop>& loops) {
  double a = loopArea(loops[0]);
  for (size_t i = 1; i < loops.size(); ++i) a -= loopArea(loops[i]);
  return a;
}

inline std::uint64_t key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// Boundary preserved (points first, in order; every boundary edge a mesh edge), every
// triangle counter-clockwise and non-degenerate, total area equal to the domain's.
inline void checkPlanarMesh(const Mesh& m, const std::vector<BoundaryLoop>& loops) {
  ASSERT_EQ(m.dimension, 2);
  ASSERT_EQ(m.params.size(), m.points.size());
  size_t idx = 0;
  size_t nb = 0;
  for (const auto& l : loops) {
    for (size_t i = 0; i < l.points.size(); ++i, ++idx) {
      ASSERT_LT(idx, m.params.size());
      EXPECT_EQ(m.params[idx], l.points[i]) << "boundary point " << idx << " moved";
    }
    nb += l.points.size();
  }
  ASSERT_EQ(m.edges.size(), nb);
  ASSERT_EQ(m.edgeRefs.size(), nb);
  std::vector<std::uint64_t> ekeys;
  double area = 0.0;
  int bad = 0;
  for (const auto& t : m.triangles) {
    for (int i = 0; i < 3; ++i) {
      ASSERT_GE(t[i], 0);
      ASSERT_LT(t[i], m.vertexCount());
      ekeys.push_back(key(t[i], t[(i + 1) % 3]));
    }
    const double o = orient2d(m.params[t[0]], m.params[t[1]], m.params[t[2]]);
    if (o <= 0.0) ++bad;
    area += 0.5 * o;
  }
  for (const auto& q : m.quads) {
    for (int i = 0; i < 4; ++i) ekeys.push_back(key(q[i], q[(i + 1) % 4]));
    for (int i = 0; i < 4; ++i) {
      const double o = orient2d(m.params[q[(i + 3) % 4]], m.params[q[i]], m.params[q[(i + 1) % 4]]);
      if (o <= 0.0) ++bad;
    }
    area += 0.5 * (orient2d(m.params[q[0]], m.params[q[1]], m.params[q[2]]) +
                   orient2d(m.params[q[0]], m.params[q[2]], m.params[q[3]]));
  }
  EXPECT_EQ(bad, 0) << "inverted or degenerate elements";
  std::vector<char> used(m.vertexCount(), 0);
  for (const auto& t : m.triangles)
    for (int v : t) used[v] = 1;
  for (const auto& q : m.quads)
    for (int v : q) used[v] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "vertices not used by any element";
  std::sort(ekeys.begin(), ekeys.end());
  size_t missing = 0;
  for (const auto& e : m.edges)
    if (!std::binary_search(ekeys.begin(), ekeys.end(), key(e[0], e[1]))) ++missing;
  EXPECT_EQ(missing, 0u) << "boundary edges missing from the mesh";
  const double expected = domainArea(loops);
  EXPECT_NEAR(area, expected, 1e-9 * expected);
}

inline bool sameMesh(const Mesh& a, const Mesh& b) {
  if (a.params.size() != b.params.size() || a.triangles != b.triangles || a.quads != b.quads || a.edges != b.edges)
    return false;
  for (size_t i = 0; i < a.params.size(); ++i)
    if (std::memcmp(a.params[i].data(), b.params[i].data(), 2 * sizeof(double)) != 0) return false;
  return true;
}

}  // namespace meshtest

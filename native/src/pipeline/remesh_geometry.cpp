#include "anisomesh/pipeline/remesh_geometry.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {
namespace {

using EdgeKey = std::pair<int, int>;
EdgeKey key(int a, int b) { return a < b ? EdgeKey{a, b} : EdgeKey{b, a}; }

}  // namespace

std::vector<BoundaryLoop> boundaryLoopsFromMesh(const Mesh& mesh) {
  for (size_t i = 0; i < mesh.points.size(); ++i)
    require(mesh.points[i].z() == 0.0, ErrorCode::InvalidDomain,
            "remeshing needs a planar mesh (z = 0), vertex " + std::to_string(i + 1) +
                " has z = " + std::to_string(mesh.points[i].z()));
  std::map<EdgeKey, int> edgeRef;
  for (size_t i = 0; i < mesh.edges.size(); ++i)
    edgeRef[key(mesh.edges[i][0], mesh.edges[i][1])] = i < mesh.edgeRefs.size() ? mesh.edgeRefs[i] : 0;

  // Directed boundary edges (a, b, ref).
  struct Directed {
    int a, b, ref;
  };
  std::vector<Directed> bnd;
  if (!mesh.triangles.empty() || !mesh.quads.empty()) {
    std::map<EdgeKey, std::pair<int, EdgeKey>> uses;  // count, one directed instance
    auto addElement = [&](const int* v, int n) {
      for (int k = 0; k < n; ++k) {
        const int a = v[k], b = v[(k + 1) % n];
        auto& u = uses[key(a, b)];
        ++u.first;
        u.second = {a, b};
      }
    };
    for (const auto& t : mesh.triangles) addElement(t.data(), 3);
    for (const auto& q : mesh.quads) addElement(q.data(), 4);
    for (const auto& u : uses)
      if (u.second.first == 1) {
        const auto it = edgeRef.find(u.first);
        bnd.push_back({u.second.second.first, u.second.second.second, it == edgeRef.end() ? 0 : it->second});
      }
  } else {
    for (size_t i = 0; i < mesh.edges.size(); ++i)
      bnd.push_back({mesh.edges[i][0], mesh.edges[i][1], i < mesh.edgeRefs.size() ? mesh.edgeRefs[i] : 0});
  }
  require(!bnd.empty(), ErrorCode::OpenContour, "the mesh has no boundary edges");

  // Undirected chaining: every boundary vertex must have exactly two boundary edges.
  std::map<int, std::vector<int>> incident;
  for (int i = 0; i < int(bnd.size()); ++i) {
    incident[bnd[i].a].push_back(i);
    incident[bnd[i].b].push_back(i);
  }
  for (const auto& v : incident) {
    const Vec3& p = mesh.points[size_t(v.first)];
    require(v.second.size() == 2, ErrorCode::OpenContour,
            "boundary vertex " + std::to_string(v.first + 1) + " " + formatPoint(p.head<2>()) + " has " +
                std::to_string(v.second.size()) +
                " boundary edges (2 expected): the boundary edges do not form closed loops");
  }
  std::vector<bool> used(bnd.size(), false);
  std::vector<BoundaryLoop> loops;
  for (int s = 0; s < int(bnd.size()); ++s) {
    if (used[size_t(s)]) continue;
    BoundaryLoop loop;
    int e = s, from = bnd[size_t(s)].a;
    while (!used[size_t(e)]) {
      used[size_t(e)] = true;
      const int to = bnd[size_t(e)].a == from ? bnd[size_t(e)].b : bnd[size_t(e)].a;
      loop.points.push_back(mesh.points[size_t(from)].head<2>());
      loop.edgeRefs.push_back(bnd[size_t(e)].ref);
      const auto& inc = incident[to];
      e = inc[0] == e ? inc[1] : inc[0];
      from = to;
    }
    require(loop.points.size() >= 3, ErrorCode::OpenContour, "a boundary loop has fewer than 3 edges");
    loops.push_back(std::move(loop));
  }

  // Outer loop first; orientation outer counter-clockwise, holes clockwise.
  std::vector<double> area;
  for (const auto& l : loops) area.push_back(signedArea(l.points));
  size_t outer = 0;
  for (size_t i = 1; i < loops.size(); ++i)
    if (std::abs(area[i]) > std::abs(area[outer])) outer = i;
  std::swap(loops[0], loops[outer]);
  std::swap(area[0], area[outer]);
  for (size_t i = 0; i < loops.size(); ++i) {
    if ((area[i] > 0) != (i == 0)) {
      BoundaryLoop& l = loops[i];
      const int n = int(l.points.size());
      BoundaryLoop rev;
      for (int k = 0; k < n; ++k) {
        rev.points.push_back(l.points[size_t(n - 1 - k)]);
        rev.edgeRefs.push_back(l.edgeRefs[size_t(((n - 2 - k) % n + n) % n)]);
      }
      l = std::move(rev);
    }
  }
  for (size_t i = 1; i < loops.size(); ++i) {
    require(pointInPolygon(loops[0].points, loops[i].points[0]), ErrorCode::InvalidDomain,
            "boundary loop at " + formatPoint(loops[i].points[0]) +
                " is outside the outer loop: several components are not supported");
    for (size_t j = 1; j < loops.size(); ++j)
      require(j == i || !pointInPolygon(loops[j].points, loops[i].points[0]), ErrorCode::InvalidDomain,
              "boundary loop at " + formatPoint(loops[i].points[0]) + " lies inside a hole: islands are not supported");
  }
  return loops;
}

Domain domainFromBoundaryLoops(const std::vector<BoundaryLoop>& loops, const LoopDomainOptions& options) {
  Domain domain;
  for (size_t li = 0; li < loops.size(); ++li) {
    const BoundaryLoop& l = loops[li];
    const int n = int(l.points.size());
    // Vertex k is a break when the ref changes there or the boundary turns sharply.
    auto isBreak = [&](int k) {
      const int prev = (k + n - 1) % n;
      if (l.edgeRefs[size_t(prev)] != l.edgeRefs[size_t(k)]) return true;
      const Vec2 u = l.points[size_t(k)] - l.points[size_t(prev)],
                 v = l.points[size_t((k + 1) % n)] - l.points[size_t(k)];
      const double turn = pm::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
      return std::abs(turn) > options.cornerAngle;
    };
    std::vector<int> breaks;
    for (int k = 0; k < n; ++k)
      if (isBreak(k)) breaks.push_back(k);
    Contour contour;
    if (breaks.empty()) {
      // A smooth closed loop: split it in three pieces so each stays a simple curve.
      breaks = {0, n / 3, (2 * n) / 3};
    }
    for (size_t b = 0; b < breaks.size(); ++b) {
      const int from = breaks[b], to = breaks[(b + 1) % breaks.size()];
      std::vector<Vec2> pts;
      int k = from;
      do {
        pts.push_back(l.points[size_t(k)]);
        k = (k + 1) % n;
      } while (k != to);
      pts.push_back(l.points[size_t(to)]);
      contour.add(std::make_shared<PolylineCurve>(std::move(pts), l.edgeRefs[size_t(from)], false));
    }
    if (li == 0)
      domain.outer = std::move(contour);
    else
      domain.holes.push_back(std::move(contour));
  }
  return domain;
}

std::vector<Metric> clampMetricSizes(const std::vector<Metric>& metrics, double hmin, double hmax) {
  std::vector<Metric> out;
  out.reserve(metrics.size());
  for (const Metric& m : metrics) {
    const MetricSizes s = m.sizes();
    double h1 = s.h1, h2 = s.h2;
    if (hmin > 0) h1 = std::max(h1, hmin), h2 = std::max(h2, hmin);
    if (hmax > 0) h1 = std::min(h1, hmax), h2 = std::min(h2, hmax);
    out.push_back(h1 == s.h1 && h2 == s.h2 ? m : Metric::fromSizes(s.alpha, h1, h2));
  }
  return out;
}

}  // namespace anisomesh

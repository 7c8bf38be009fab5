#include "anisomesh/mesh/quality.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "anisomesh/controlspace/concurrency.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/mesh/element_edges.h"
#include "anisomesh/mesh/predicates.h"
#include "mesh_internal.h"

namespace anisomesh {
namespace {

void addToHistogram(QualityReport& r, double q) {
  const int bin = q <= 0.0 ? 0 : std::min(9, static_cast<int>(q * 10.0));
  ++r.qualityHistogram[bin];
}

}  // namespace

std::vector<std::array<int, 2>> distinctElementEdges(const Mesh& mesh) { return elementEdges(mesh).edges; }

QualityReport measureQuality(const Mesh& mesh, const ControlSpace& controlSpace, ElementMeasures* perItem) {
  QualityReport r;
  const int nv = mesh.vertexCount();
  r.vertices = nv;
  r.triangles = static_cast<int>(mesh.triangles.size());
  r.quads = static_cast<int>(mesh.quads.size());
  std::vector<Vec2> uv(nv);
  for (int v = 0; v < nv; ++v)
    uv[v] =
        mesh.params.size() == static_cast<size_t>(nv) ? mesh.params[v] : Vec2(mesh.points[v].x(), mesh.points[v].y());
  std::vector<SymMt> mt(nv);
  // Meshes come out spatially ordered, so each query starts its search where the previous
  // one of its chunk ended (metricAtNear: the same values as metricAt).
  if (queriesAreConcurrent(controlSpace))  // the vertices' metrics in parallel chunks
    parallelChunks(size_t(nv), 4096, [&](size_t, size_t b, size_t e) {
      int hint = -1;
      for (size_t v = b; v < e; ++v) mt[v] = SymMt::from(controlSpace.metricAtNear(uv[v], hint).transform());
    });
  else {
    int hint = -1;
    for (int v = 0; v < nv; ++v) mt[v] = SymMt::from(controlSpace.metricAtNear(uv[v], hint).transform());
  }

  const ElementEdges elementEdgeList = elementEdges(mesh);
  const std::vector<std::array<int, 2>>& edges = elementEdgeList.edges;
  r.edges = static_cast<int>(edges.size());
  r.largestNeighbourSizeRatio = largestNeighbourSizeRatio(mesh, elementEdgeList);
  if (perItem) {
    perItem->edges = edges;
    perItem->edgeLength.resize(edges.size());
    perItem->quality.clear();
    perItem->quality.reserve(mesh.triangles.size() + mesh.quads.size());
    perItem->vertexMinSize.resize(nv);
    // 1 / the largest eigenvalue of Mt.
    for (int v = 0; v < nv; ++v) {
      const SymMt& m = mt[v];
      perItem->vertexMinSize[v] = 1.0 / (0.5 * (m.a + m.c) + std::hypot(0.5 * (m.a - m.c), m.b));
    }
  }
  double lsum = 0.0;
  int in1 = 0, in2 = 0;
  r.edgeLengthMin = edges.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  // The per-edge and per-triangle measures in parallel chunks, their sums, counts and
  // extremes in element order on this thread: the same bits for any thread count.
  std::vector<double> lengths(edges.size());
  parallelChunks(edges.size(), 16384, [&](size_t, size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) {
      const int p = edges[k][0], q = edges[k][1];
      lengths[k] = SymMt::average2(mt[p], mt[q]).length(uv[q] - uv[p]);
    }
  });
  for (size_t e = 0; e < edges.size(); ++e) {
    const double l = lengths[e];
    if (perItem) perItem->edgeLength[e] = l;
    lsum += l;
    r.edgeLengthMin = std::min(r.edgeLengthMin, l);
    r.edgeLengthMax = std::max(r.edgeLengthMax, l);
    if (l >= std::sqrt(0.5) && l <= std::sqrt(2.0)) ++in1;
    if (l >= 0.6 && l <= 1.3) ++in2;
  }
  if (!edges.empty()) {
    r.edgeLengthMean = lsum / edges.size();
    r.edgesWithinSqrt2 = static_cast<double>(in1) / edges.size();
    r.edgesWithin06_13 = static_cast<double>(in2) / edges.size();
  }

  double qsum = 0.0, tsum = 0.0, qdsum = 0.0;
  r.qualityMin = r.triangleQualityMin = r.quadQualityMin = std::numeric_limits<double>::infinity();
  std::vector<double> quality(mesh.triangles.size());
  std::vector<std::uint8_t> orientation(mesh.triangles.size());  // orient2d: 0 negative, 1 zero, 2 positive
  parallelChunks(mesh.triangles.size(), 16384, [&](size_t, size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) {
      const auto& t = mesh.triangles[k];
      const SymMt m = SymMt::average3(mt[t[0]], mt[t[1]], mt[t[2]]);
      quality[k] = metricTriangleQuality(m, uv[t[0]], uv[t[1]], uv[t[2]]);
      const double o = orient2d(uv[t[0]], uv[t[1]], uv[t[2]]);
      orientation[k] = static_cast<std::uint8_t>(o < 0.0 ? 0 : (o == 0.0 ? 1 : 2));  // NaN: 2, as before
    }
  });
  for (size_t k = 0; k < mesh.triangles.size(); ++k) {
    const double q = quality[k];
    const std::uint8_t o = orientation[k];
    if (o == 0)
      ++r.inverted;
    else if (o == 1 || q < 1e-3)
      ++r.degenerate;
    r.triangleQualityMin = std::min(r.triangleQualityMin, q);
    if (perItem) perItem->quality.push_back(q);
    tsum += q;
    addToHistogram(r, q);
  }
  for (const auto& qd : mesh.quads) {
    Vec2 p[4];
    SymMt m{0.0, 0.0, 0.0};
    for (int k = 0; k < 4; ++k) {
      p[k] = uv[qd[k]];
      m.a += 0.25 * mt[qd[k]].a;
      m.b += 0.25 * mt[qd[k]].b;
      m.c += 0.25 * mt[qd[k]].c;
    }
    const double q = metricQuadQuality(m, p);
    bool inv = false, flat = false;
    for (int k = 0; k < 4; ++k) {
      const double o = orient2d(p[(k + 3) % 4], p[k], p[(k + 1) % 4]);
      inv = inv || o < 0.0;
      flat = flat || o == 0.0;
    }
    if (inv)
      ++r.inverted;
    else if (flat || q < 1e-3)
      ++r.degenerate;
    r.quadQualityMin = std::min(r.quadQualityMin, q);
    if (perItem) perItem->quality.push_back(q);
    qdsum += q;
    addToHistogram(r, q);
  }
  qsum = tsum + qdsum;
  const int ne = r.triangles + r.quads;
  r.qualityMin = std::min(r.triangleQualityMin, r.quadQualityMin);
  if (ne == 0) r.qualityMin = 0.0;
  r.qualityMean = ne ? qsum / ne : 0.0;
  r.triangleQualityMean = r.triangles ? tsum / r.triangles : 0.0;
  if (!r.triangles) r.triangleQualityMin = 0.0;
  r.quadQualityMean = r.quads ? qdsum / r.quads : 0.0;
  if (!r.quads) r.quadQualityMin = 0.0;
  return r;
}

std::vector<double> triangleMetricAreas(const Mesh& mesh, const ControlSpace& controlSpace) {
  const int nv = mesh.vertexCount();
  const bool useParams = mesh.params.size() == static_cast<size_t>(nv);
  std::vector<Vec2> uv(nv);
  std::vector<SymMt> mt(nv);
  int hint = -1;  // metricAtNear: the same values, the search started at the previous vertex
  for (int v = 0; v < nv; ++v) {
    uv[v] = useParams ? mesh.params[v] : Vec2(mesh.points[v].x(), mesh.points[v].y());
    mt[v] = SymMt::from(controlSpace.metricAtNear(uv[v], hint).transform());
  }
  std::vector<double> out;
  out.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const SymMt m = SymMt::average3(mt[t[0]], mt[t[1]], mt[t[2]]);
    const Vec2 e1 = uv[t[1]] - uv[t[0]], e2 = uv[t[2]] - uv[t[0]];
    out.push_back(0.5 * (e1.x() * e2.y() - e1.y() * e2.x()) * m.det());
  }
  return out;
}

}  // namespace anisomesh

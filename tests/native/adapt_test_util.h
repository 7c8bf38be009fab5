#pragma once
// Meshes for the adaptation tests: jittered grids and mesher-made unstructured meshes.
#include <cmath>
#include <cstdint>
#include <vector>

#include "anisomesh/mesh/mesh.h"
#include "anisomesh/metric/metric.h"
#include "anisomesh/pipeline/pipeline.h"

namespace adapttest {

using namespace anisomesh;

// An n x n grid of [x0, x0 + w] x [y0, y0 + w], squares split by alternating diagonals,
// interior vertices moved by up to jitter * cell size (deterministic pseudo-random).
inline Mesh gridMesh(int n, double jitter = 0.0, double w = 1.0, double x0 = 0.0, double y0 = 0.0) {
  Mesh m;
  std::uint64_t s = 12345;
  auto rnd = [&s]() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(s >> 11) / double(1ULL << 53) - 0.5;
  };
  const double h = w / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double x = x0 + i * h, y = y0 + j * h;
      if (i > 0 && i < n && j > 0 && j < n) x += jitter * h * rnd(), y += jitter * h * rnd();
      m.points.emplace_back(x, y, 0.0);
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
      m.triangleRefs.push_back(0);
      m.triangleRefs.push_back(0);
    }
  return m;
}

// A mesher-made mesh of the unit square (or [0, w]^2) under one metric (remesh of a grid).
inline Mesh remeshedSquare(const Metric& metric, double w = 1.0) {
  const Mesh coarse = gridMesh(2, 0.0, w);
  return remesh(coarse, std::vector<Metric>(coarse.points.size(), metric));
}

}  // namespace adapttest

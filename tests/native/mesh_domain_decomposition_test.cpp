// Planar domain decomposition (mesh/domain_decomposition.h): the parts tile the domain,
// their chords are shared point for point, and the merged mesh is one conforming mesh,
// the same for any thread count, of the whole mesh's quality.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>

#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/mesh/domain_decomposition.h"
#include "mesh_test_util.h"

using namespace anisomesh;
using namespace meshtest;

namespace {

struct DecompositionThreadCountGuard {
  int saved = threadCount();
  ~DecompositionThreadCountGuard() { setThreadCount(saved); }
};

// A rotated shear layer along the diagonal of [0, 2] x [0, 1] (aspect ratio 8 at it).
Metric shear(const Vec2& p) {
  const double d = std::abs(p.y() - 0.5 * p.x());
  return Metric::fromSizes(std::atan(0.5), 0.024, std::min(0.024, 0.003 + 0.1 * d));
}

std::unique_ptr<QuadtreeControlSpace> shearSpace() {
  QuadtreeOptions o;
  o.maxLevel = 8;
  auto cs = std::make_unique<QuadtreeControlSpace>(Box2{{0.0, 0.0}, {2.0, 1.0}}, o);
  ContinuousInsertionOptions c;
  c.threshold = 0.3;
  c.sampleThreshold = 0.05;
  insertMetricFunction(*cs, shear, c);
  return cs;
}

// The rectangle with two round holes (clockwise), one of them on the layer.
std::vector<BoundaryLoop> domainWithHoles(const ControlSpace& cs) {
  return {metricPolygonLoop({{0, 0}, {2, 0}, {2, 1}, {0, 1}}, cs), circleLoop({0.6, 0.3}, 0.12, 60, true),
          circleLoop({1.4, 0.7}, 0.1, 48, true, 11)};
}

// Every edge of the mesh is used by one element (a boundary edge) or two (inner).
void expectConforming(const Mesh& m) {
  std::map<std::uint64_t, int> uses;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i) ++uses[key(t[i], t[(i + 1) % 3])];
  std::vector<std::uint64_t> boundary;
  for (const auto& e : m.edges) boundary.push_back(key(e[0], e[1]));
  std::sort(boundary.begin(), boundary.end());
  int bad = 0;
  for (const auto& [k, n] : uses) {
    const bool onBoundary = std::binary_search(boundary.begin(), boundary.end(), k);
    if (n != (onBoundary ? 1 : 2)) ++bad;
  }
  EXPECT_EQ(bad, 0) << "edges not shared by exactly two triangles (one on the boundary)";
  std::vector<std::pair<double, double>> pts;
  for (const auto& p : m.params) pts.emplace_back(p.x(), p.y());
  std::sort(pts.begin(), pts.end());
  EXPECT_EQ(std::adjacent_find(pts.begin(), pts.end()), pts.end()) << "two mesh points at one place";
}

double partArea(const DomainParts& d, const DomainPart& part) {
  double a = 0.0;
  for (const auto& loop : part.loops) {
    BoundaryLoop l;
    for (int id : loop) l.points.push_back(d.points[id]);
    a += (&loop == &part.loops[0] ? 1.0 : -1.0) * loopArea(l);
  }
  return a;
}

}  // namespace

// The parts tile the domain: their areas sum to it, every input edge is in one part once,
// every chord edge in two parts in opposite directions.
TEST(DomainDecomposition, PartsTileTheDomainAndShareTheirChords) {
  const auto cs = shearSpace();
  const auto loops = domainWithHoles(*cs);
  DomainDecompositionOptions o;
  o.partElements = 2000;
  const DomainParts d = decomposeDomain(loops, *cs, o);
  ASSERT_GE(d.parts.size(), 4u);
  EXPECT_GE(
      d.estimatedElements,
      static_cast<double>(d.parts.size() *
                          o.partElements));  // leaves: the largest power of 2 with leaves x partElements <= estimate
  double area = 0.0;
  std::map<std::pair<int, int>, int> inputEdges, chordEdges;
  for (const DomainPart& p : d.parts) {
    area += partArea(d, p);
    EXPECT_GT(partArea(d, p), 0.0);
    for (size_t l = 0; l < p.loops.size(); ++l)
      for (size_t i = 0; i < p.loops[l].size(); ++i) {
        const int a = p.loops[l][i], b = p.loops[l][(i + 1) % p.loops[l].size()];
        ++(p.chord[l][i] ? chordEdges : inputEdges)[{a, b}];
      }
  }
  EXPECT_NEAR(area, domainArea(loops), 1e-12 * domainArea(loops));
  size_t nInput = 0;
  for (const auto& l : loops) nInput += l.points.size();
  EXPECT_EQ(inputEdges.size(), nInput);
  for (const auto& [e, n] : inputEdges) EXPECT_EQ(n, 1);
  ASSERT_FALSE(chordEdges.empty());
  for (const auto& [e, n] : chordEdges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(chordEdges.count({e.second, e.first}), 1u) << "chord edge " << e.first << "-" << e.second << " unmatched";
  }
}

// The merged mesh: boundary kept, conforming, same for 1, 2 and 4 threads, and of the
// quality of the domain meshed whole.
TEST(DomainDecomposition, MergedMeshIsConformingAndTheSameForAnyThreadCount) {
  DecompositionThreadCountGuard guard;
  const auto cs = shearSpace();
  const auto loops = domainWithHoles(*cs);
  PlanarMesherOptions whole;
  whole.partElements = 0;
  const Mesh reference = meshPlanarBoundary(loops, *cs, whole);
  const QualityReport rq = measureQuality(reference, *cs);
  PlanarMesherOptions split;
  split.partElements = 2000;
  Mesh first;
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    const Mesh m = meshPlanarBoundary(loops, *cs, split);
    if (threads == 1) {
      checkPlanarMesh(m, loops);
      expectConforming(m);
      EXPECT_FALSE(sameMesh(m, reference));  // it was decomposed
      const QualityReport q = measureQuality(m, *cs);
      EXPECT_EQ(q.inverted, 0);
      EXPECT_NEAR(static_cast<double>(q.triangles), static_cast<double>(rq.triangles), 0.03 * rq.triangles);
      EXPECT_GE(q.edgesWithinSqrt2, rq.edgesWithinSqrt2 - 0.01);
      EXPECT_GE(q.qualityMean, rq.qualityMean - 0.01);
      EXPECT_GE(q.qualityMin, 0.5 * rq.qualityMin);
      first = m;
      continue;
    }
    EXPECT_TRUE(sameMesh(m, first)) << threads << " threads";
  }
}

// A domain estimated below twice partElements is meshed whole: the same mesh as without decomposition.
TEST(DomainDecomposition, SmallDomainsAreMeshedWhole) {
  const auto cs = shearSpace();
  const auto loops = domainWithHoles(*cs);
  PlanarMesherOptions whole, big;
  whole.partElements = 0;
  big.partElements = 1000000;
  EXPECT_TRUE(sameMesh(meshPlanarBoundary(loops, *cs, whole), meshPlanarBoundary(loops, *cs, big)));
  DomainDecompositionOptions o;
  o.partElements = 1000000;
  EXPECT_EQ(decomposeDomain(loops, *cs, o).parts.size(), 1u);
  // Loops the mesher refuses stay one part (and the mesher names the error).
  std::vector<BoundaryLoop> bad{makeLoop({{0, 0}, {1, 0}})};
  o.partElements = 10;
  EXPECT_EQ(decomposeDomain(bad, *cs, o).parts.size(), 1u);
  PlanarMesherOptions small;
  small.partElements = 10;
  EXPECT_THROW(meshPlanarBoundary(bad, *cs, small), Error);
}

// Chords cross a layer of aspect ratio 100 at 30 degrees (the cuts are axis-aligned, the
// layer is rotated): the parts' meshes along the chords stay as good as the whole mesh.
TEST(DomainDecomposition, ChordsAcrossAStrongLayerKeepTheQuality) {
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  AnalyticControlSpace cs(Box2{{0.0, 0.0}, {1.0, 1.0}}, [=](const Vec2& p) {
    const double v = -s * (p.x() - 0.5) + c * (p.y() - 0.5);
    return Metric::fromSizes(M_PI / 6, 0.01, std::min(0.01, 0.0001 + 0.02 * std::abs(v)));
  });
  const std::vector<BoundaryLoop> loops{metricPolygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, cs)};
  PlanarMesherOptions whole, split;
  whole.partElements = 0;
  split.partElements = 4000;
  const Mesh a = meshPlanarBoundary(loops, cs, whole), b = meshPlanarBoundary(loops, cs, split);
  checkPlanarMesh(b, loops);
  expectConforming(b);
  EXPECT_FALSE(sameMesh(a, b));
  const QualityReport qa = measureQuality(a, cs), qb = measureQuality(b, cs);
  std::cout << "whole " << qa.triangles << " min Q " << qa.qualityMin << " / decomposed " << qb.triangles << " min Q "
            << qb.qualityMin << "\n";
  EXPECT_GE(qb.qualityMin, 0.8 * qa.qualityMin);
  EXPECT_GE(qb.edgesWithinSqrt2, qa.edgesWithinSqrt2 - 0.01);
}

// A curved front (y = 0.5 + 0.1 sin 2 pi x, aspect ratio up to 10): no straight cut meets
// it square but at its crests, so the parts are cut along its principal lines. Every part
// asked for is made, every chord edge runs along or across the stretching where it is
// anisotropic, and the merged mesh keeps the quality of the whole mesh, for any thread count.
TEST(DomainDecomposition, CurvedLayerIsCutAlongItsPrincipalLines) {
  DecompositionThreadCountGuard guard;
  AnalyticControlSpace cs(Box2{{0.0, 0.0}, {1.0, 1.0}}, [](const Vec2& p) {
    const double slope = 0.2 * M_PI * std::cos(2.0 * M_PI * p.x()), g = std::hypot(slope, 1.0);
    const double d = (p.y() - 0.5 - 0.1 * std::sin(2.0 * M_PI * p.x())) / g;
    return Metric::fromSizes(std::atan(slope), 0.02, std::min(0.02, 0.002 + 0.03 * std::abs(d)));
  });
  const std::vector<BoundaryLoop> loops{metricPolygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, cs)};
  DomainDecompositionOptions o;
  o.partElements = 500;
  o.maxParts = 8;
  const DomainParts d = decomposeDomain(loops, cs, o);
  ASSERT_GE(d.estimatedElements, 8000.0);
  EXPECT_EQ(d.parts.size(), 8u);
  int chordEdges = 0, oblique = 0;
  for (const DomainPart& p : d.parts)
    for (size_t l = 0; l < p.loops.size(); ++l)
      for (size_t i = 0; i < p.loops[l].size(); ++i) {
        if (!p.chord[l][i]) continue;
        const Vec2 a = d.points[p.loops[l][i]], b = d.points[p.loops[l][(i + 1) % p.loops[l].size()]];
        const Metric m = cs.metricAt(0.5 * (a + b));
        ++chordEdges;
        // within 2 degrees (and rounding) of a principal direction: |sin 2 theta| <= sin 4 degrees
        const double theta = std::atan2((b - a).y(), (b - a).x()) - m.sizes().alpha;
        if (m.aspectRatio() > 1.5 && std::fabs(std::sin(2.0 * theta)) > 0.0698 + 1e-3) ++oblique;
      }
  EXPECT_GT(chordEdges, 0);
  EXPECT_EQ(oblique, 0) << "of " << chordEdges << " chord edges";
  PlanarMesherOptions whole, split;
  whole.partElements = 0;
  split.partElements = o.partElements;
  const Mesh a = meshPlanarBoundary(loops, cs, whole);
  const QualityReport qa = measureQuality(a, cs);
  Mesh first;
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    const Mesh m = meshPlanarBoundary(loops, cs, split);
    if (threads > 1) {
      EXPECT_TRUE(sameMesh(m, first)) << threads << " threads";
      continue;
    }
    checkPlanarMesh(m, loops);
    expectConforming(m);
    const QualityReport q = measureQuality(m, cs);
    std::cout << "whole " << qa.triangles << " min Q " << qa.qualityMin << " / " << d.parts.size() << " parts "
              << q.triangles << " min Q " << q.qualityMin << "\n";
    // The cuts' vertices are fixed in both parts; without the seam polish after the merge
    // one triangle next to a chord across the layer reached 0.62 (whole mesh 0.80), with it
    // 0.79.
    EXPECT_GE(q.qualityMin, 0.95 * qa.qualityMin);
    EXPECT_GE(q.qualityMean, qa.qualityMean - 0.005);
    EXPECT_GE(q.edgesWithinSqrt2, qa.edgesWithinSqrt2 - 0.005);
    first = m;
  }
}

// A vortex (principal directions turning around the centre, aspect ratio 6): principal
// lines circle instead of leaving a part, and straight cuts are refused near the centre.
// The decomposition still ends with parts that tile the domain, and the merged mesh is
// conforming.
TEST(DomainDecomposition, VortexMetricEndsWithValidParts) {
  AnalyticControlSpace cs(Box2{{0.0, 0.0}, {1.0, 1.0}}, [](const Vec2& p) {
    const double r = std::hypot(p.x() - 0.5, p.y() - 0.5);
    return Metric::fromSizes(std::atan2(p.y() - 0.5, p.x() - 0.5), 0.0025 + 0.012 * r, 0.015 + 0.07 * r);
  });
  const std::vector<BoundaryLoop> loops{metricPolygonLoop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, cs)};
  DomainDecompositionOptions o;
  o.partElements = 300;
  o.maxParts = 16;
  const DomainParts d = decomposeDomain(loops, cs, o);
  std::cout << "estimated " << d.estimatedElements << " elements, " << d.parts.size() << " parts\n";
  ASSERT_GE(d.estimatedElements, 9600.0);
  EXPECT_GE(d.parts.size(), 2u);
  double area = 0.0;
  std::map<std::pair<int, int>, int> chordEdges;
  for (const DomainPart& p : d.parts) {
    EXPECT_GT(partArea(d, p), 0.0);
    area += partArea(d, p);
    for (size_t l = 0; l < p.loops.size(); ++l)
      for (size_t i = 0; i < p.loops[l].size(); ++i)
        if (p.chord[l][i]) ++chordEdges[{p.loops[l][i], p.loops[l][(i + 1) % p.loops[l].size()]}];
  }
  EXPECT_NEAR(area, 1.0, 1e-12);
  for (const auto& [e, n] : chordEdges) EXPECT_EQ(chordEdges.count({e.second, e.first}), 1u);
  PlanarMesherOptions split;
  split.partElements = o.partElements;
  const Mesh m = meshPlanarBoundary(loops, cs, split);
  checkPlanarMesh(m, loops);
  expectConforming(m);
}

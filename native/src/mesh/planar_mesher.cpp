// Metric Delaunay mesher of a planar domain: the driver (the stages, each in its own file
// under mesh/planar/, are described in mesh/planar/mesher_impl.h).
#include "anisomesh/mesh/planar_mesher.h"

#include <exception>

#include "anisomesh/controlspace/concurrency.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/mesh/all_quad_split.h"
#include "anisomesh/mesh/domain_decomposition.h"

#include "planar/mesher_impl.h"

namespace anisomesh {
namespace planar {

double Mesher::start() {
  validate();
  auto t0 = Clock::now();
  elementRatio_ = opt_.allQuads ? 2.0 : (opt_.quads ? 0.6 : 1.0);
  checkProgress(0.0);
  boundaryTriangulation();
  vhint_.assign(vx_.size(), -1);
  for (int v = kSuper; v < static_cast<int>(vx_.size()); ++v) {
    vx_[v].m = queryMetric(vx_[v].p);
    vhint_[v] = queryHint_;
  }

  if (opt_.boundaryOnly) {
    timings_.boundary = secondsSince(t0);
  } else {
    // Budget check before the expensive work: one unit equilateral triangle per sqrt(3)/4 of metric area.
    const double metricArea = estimateMetricArea();
    timings_.boundary = secondsSince(t0);
    estimate_ = std::max(static_cast<double>(liveTriangles()), trianglesOfMetricArea(metricArea));
    timings_.estimatedElements = saturatedInt64(estimate_ * elementRatio_);
    if (estimate_ * elementRatio_ > static_cast<double>(opt_.maxElements)) {
      std::ostringstream os;
      os << "meshPlanarBoundary: the requested mesh needs about " << timings_.estimatedElements
         << " elements, above the element budget of " << opt_.maxElements;
      throw Error(ErrorCode::ElementBudgetExceeded, os.str());
    }
    checkProgress(0.1);
  }
  return estimate_ * elementRatio_;
}

Mesh Mesher::finish() {
  Mesh mesh;
  if (opt_.boundaryOnly) {
    mesh = output();
    keepBoundaryTriangulation();
  } else {
    auto t0 = Clock::now();
    // Room for the expected mesh (the estimate is within ~10%): no reallocation copies.
    const size_t expect = static_cast<size_t>(std::min(1.15 * estimate_, static_cast<double>(opt_.maxElements))) + 1024;
    tri_.reserve(expect);
    forbid_.reserve(expect);
    stamp_.reserve(expect);
    queued_.reserve(expect);
    cache_.reserve(expect);
    vx_.reserve(expect / 2 + nBoundary_);
    vhint_.reserve(expect / 2 + nBoundary_);
    vbnd_.reserve(expect / 2 + nBoundary_);
    vtri_.reserve(expect / 2 + nBoundary_);
    insertInnerNodes();
    timings_.insertion = secondsSince(t0);
    t0 = Clock::now();
    renumberSpatially();
    improve();
    timings_.improvement = secondsSince(t0);
    mesh = output();
    if (opt_.quads || opt_.allQuads) {
      t0 = Clock::now();
      std::vector<SymMt> vm;
      vm.reserve(vx_.size() - kSuper);
      for (size_t v = kSuper; v < vx_.size(); ++v)
        if (vbnd_[v] != 2) vm.push_back(vx_[v].m);
      convertToQuads(mesh, vm, opt_.minQuadQuality);
      if (opt_.allQuads) splitIntoAllQuads(mesh, loopEdgeMidpoints(loops_));
      timings_.quads = secondsSince(t0);
    }
  }
  if (mesh.elementCount() > opt_.maxElements) {
    std::ostringstream os;
    os << "meshPlanarBoundary: the mesh has " << mesh.elementCount() << " elements, above the element budget of "
       << opt_.maxElements;
    throw Error(ErrorCode::ElementBudgetExceeded, os.str());
  }
  checkProgress(1.0);
  if (opt_.timings) *opt_.timings = timings_;
  return mesh;
}

}  // namespace planar

Mesh meshPlanarBoundary(const std::vector<BoundaryLoop>& loops, const ControlSpace& controlSpace,
                        const PlanarMesherOptions& options) {
  planar::Mesher mesher(loops, controlSpace, options);
  const bool mayDecompose = options.partElements > 0 && !options.boundaryOnly && !options.allQuads;
  DomainDecompositionOptions d;
  d.partElements = options.partElements;
  // With threads to spare, the decomposition is planned while the whole domain's boundary
  // triangulation is built (its first level has one part: a thread would idle), and
  // dropped, with any error it raised, when the estimate keeps the domain whole. Only for
  // boundaries long enough to enclose 2 partElements at their own spacing (a square of n
  // points holds about n^2 / 8 triangles): small domains would wait for its samples. Not
  // on a control space that tallies its queries (a dropped plan's would count only with
  // threads), nor where the threads are already busy (a patch among patches).
  double boundaryPoints = 0.0;
  for (const BoundaryLoop& l : loops) boundaryPoints += static_cast<double>(l.points.size());
  const bool ahead = mayDecompose && threadCount() > 1 && !insideParallelChunks() &&
                     queriesAreConcurrent(controlSpace) && !controlSpace.countsQueries() &&
                     boundaryPoints * boundaryPoints >= 16.0 * static_cast<double>(options.partElements);
  DomainParts parts;
  std::exception_ptr decompositionFailure;
  double estimate = 0.0;
  if (ahead) {
    parallelInvoke([&] { estimate = mesher.start(); },
                   [&] {
                     try {
                       parts = decomposeDomain(loops, controlSpace, d);
                     } catch (...) {
                       decompositionFailure = std::current_exception();
                     }
                   });
  } else {
    estimate = mesher.start();
  }
  // Only large domains pay for the decomposition's samples (small ones keep their queries).
  if (mayDecompose && estimate >= 2.0 * static_cast<double>(options.partElements)) {
    if (decompositionFailure) std::rethrow_exception(decompositionFailure);
    if (!ahead) parts = decomposeDomain(loops, controlSpace, d);
    if (parts.parts.size() > 1) {
      try {
        return meshDomainParts(loops, parts, controlSpace, options);
      } catch (const Error& e) {
        // A part the mesher refuses (a chord too close to a boundary it did not see) must
        // not fail a domain the mesher takes whole: mesh it whole, as without decomposition.
        if (e.code() == ErrorCode::ElementBudgetExceeded || e.code() == ErrorCode::Cancelled) throw;
      }
    }
  }
  return mesher.finish();
}

}  // namespace anisomesh

// The end-to-end runs; the only file of the pipeline that calls the planar mesher.
#include "anisomesh/pipeline/pipeline.h"

#include <chrono>

#include "anisomesh/geometry/discretize.h"
#include "anisomesh/pipeline/case_control_space.h"
#include "anisomesh/pipeline/mesh_metric_field.h"
#include "anisomesh/pipeline/remesh_geometry.h"

namespace anisomesh {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Discretizes the domain and meshes it, filling the report.
Mesh meshDomain(const Domain& domain, const ControlSpace& cs, const PlanarMesherOptions& mesher,
                PipelineReport* report, std::chrono::steady_clock::time_point t0) {
  DiscretizeOptions d;
  d.maxSegments = std::max<std::int64_t>(1, mesher.maxElements);
  const std::vector<BoundaryLoop> loops = discretizeDomain(domain, cs, d);
  if (report) {
    report->boundaryLoops = int(loops.size());
    report->boundaryPoints = 0;
    for (const auto& l : loops) report->boundaryPoints += int(l.points.size());
    report->secondsGeometry = secondsSince(t0);
  }
  const auto t1 = std::chrono::steady_clock::now();
  Mesh mesh = meshPlanarBoundary(loops, cs, mesher);
  if (report) report->secondsMeshing = secondsSince(t1);
  return mesh;
}

}  // namespace

PlanarMesherOptions mesherOptionsFromCase(const CaseSpec& spec) {
  PlanarMesherOptions o;
  o.quads = spec.options.quads || spec.options.allQuads;
  o.allQuads = spec.options.allQuads;
  o.maxElements = spec.options.maxElements;
  return o;
}

Mesh meshCase(const CaseSpec& spec, PipelineReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  validateDomain(spec.domain);
  const std::unique_ptr<ControlSpace> cs = buildCaseControlSpace(spec);
  if (report && spec.controlSpace.kind == "background")
    report->notes.push_back("controlSpace.kind 'background' is served by the analytic stand-in for now");
  return meshDomain(spec.domain, *cs, mesherOptionsFromCase(spec), report, t0);
}

Mesh remesh(const Mesh& input, const std::vector<Metric>& metrics, const RemeshOptions& options,
            PipelineReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  const Domain domain = domainFromBoundaryLoops(boundaryLoopsFromMesh(input));
  validateDomain(domain);
  const TriangleMeshMetricField field(input, clampMetricSizes(metrics, options.hmin, options.hmax));
  if (report && options.hgrad > 0) report->notes.push_back("hgrad is not applied yet (no metric gradation in remesh)");
  return meshDomain(domain, field, options.mesher, report, t0);
}

}  // namespace anisomesh

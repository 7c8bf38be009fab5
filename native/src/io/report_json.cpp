#include "anisomesh/io/report_json.h"

#include "anisomesh/pipeline/mesh_statistics.h"

namespace anisomesh {

nlohmann::json qualityReportToJson(const QualityReport& r) {
  nlohmann::json j;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["quads"] = r.quads;
  j["edges"] = r.edges;
  j["edgeLength"] = {{"min", r.edgeLengthMin},
                     {"mean", r.edgeLengthMean},
                     {"max", r.edgeLengthMax},
                     {"fractionWithinSqrt2", r.edgesWithinSqrt2},
                     {"fractionWithin0.6_1.3", r.edgesWithin06_13}};
  j["quality"] = {{"min", r.qualityMin},
                  {"mean", r.qualityMean},
                  {"triangleMin", r.triangleQualityMin},
                  {"triangleMean", r.triangleQualityMean},
                  {"quadMin", r.quadQualityMin},
                  {"quadMean", r.quadQualityMean},
                  {"histogram", r.qualityHistogram}};
  j["inverted"] = r.inverted;
  j["degenerate"] = r.degenerate;
  j["timings"] = {{"boundary", r.timings.boundary},
                  {"insertion", r.timings.insertion},
                  {"improvement", r.timings.improvement},
                  {"quads", r.timings.quads},
                  {"estimatedElements", r.timings.estimatedElements}};
  return j;
}

nlohmann::json pipelineStatsJson(const Mesh& mesh, const ControlSpace& cs, const PipelineReport& r) {
  QualityReport q = measureQuality(mesh, cs);
  q.timings = r.mesherTimings;
  nlohmann::json j = qualityReportToJson(q);
  j["largestNeighbourSizeRatio"] = q.largestNeighbourSizeRatio;
  j["boundaryLoops"] = r.boundaryLoops;
  j["boundaryPoints"] = r.boundaryPoints;
  j["controlElements"] = r.controlElements;
  j["controlNodes"] = r.controlNodes;
  j["pipelineSeconds"] = {{"geometry", r.secondsGeometry},
                          {"controlSpace", r.secondsControlSpace},
                          {"discretization", r.secondsDiscretization},
                          {"boundaryUpdates", r.secondsUpdates},
                          {"meshing", r.secondsMeshing}};
  j["boundaryUpdates"] = {{"rounds", r.updateRounds},
                          {"converged", r.updatesConverged},
                          {"shortSegments", r.shortSegments},
                          {"shortSegmentSources", r.shortSegmentSources},
                          {"invalidSegments", r.invalidSegments},
                          {"rediscretizedContours", r.rediscretizedContours},
                          {"chordSources", r.chordSources},
                          {"proximitySources", r.proximitySources},
                          {"refinedElements", r.refinedElements},
                          {"maxChordDeviation", r.maxChordDeviation}};
  if (r.cacheHits + r.cacheMisses > 0) j["queryCache"] = {{"hits", r.cacheHits}, {"misses", r.cacheMisses}};
  j["notes"] = r.notes;
  return j;
}

nlohmann::json surfaceMeshReportToJson(const SurfaceMeshReport& r) {
  const Surface3DQuality& q = r.quality;
  return nlohmann::json{{"patches", r.patches},
                        {"rounds", r.rounds},
                        {"invalidations", r.invalidations},
                        {"boundaryUpdates",
                         {{"converged", r.converged},
                          {"chordSources", r.chordSources},
                          {"proximitySources", r.proximitySources},
                          {"shortSegmentSources", r.shortSegmentSources}}},
                        {"vertices", r.vertices},
                        {"triangles", r.triangles},
                        {"patchTriangles", r.patchTriangles},
                        {"sharedEdges", r.sharedEdges},
                        {"crossSharedSizeRatioMax", r.crossSharedSizeRatioMax},
                        {"quality3d",
                         {{"edges", q.edges},
                          {"edgesWithinSqrt2", q.edgesWithinSqrt2},
                          {"edgeLengthMin", q.edgeLengthMin},
                          {"edgeLengthMean", q.edgeLengthMean},
                          {"edgeLengthMax", q.edgeLengthMax},
                          {"qualityMean", q.qualityMean},
                          {"qualityMin", q.qualityMin},
                          {"chordDeviationMax", q.chordDeviationMax},
                          {"chordDeviationMaxRelative", q.chordDeviationMaxRelative},
                          {"edgeChordDeviationMax", q.edgeChordDeviationMax},
                          {"isoChordDeviationMax", q.isoChordDeviationMax},
                          {"inverted", q.inverted}}},
                        {"curvatureEvaluations", r.curvatureEvaluations},
                        {"curvatureSeconds", r.curvatureSeconds},
                        {"controlSpaceQueries", r.controlSpaceQueries},
                        {"controlSpaceSeconds", r.controlSpaceSeconds},
                        {"secondsTotal", r.secondsTotal}};
}

}  // namespace anisomesh

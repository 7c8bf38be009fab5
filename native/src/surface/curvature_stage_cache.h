#pragma once
// Surface meshing (internal): the control space of a patch after its curvature stage
// (main-level grid and refinement on the surface's curvature and the 3D sources, the
// contours' curvature, then smoothed to the gradation ratio; before the 2D sources) kept from
// earlier runs. While a 2D source is dragged on a patch, the surface and its sizing stay
// the same, so every run after the first starts from a copy instead of evaluating the
// curvature and smoothing the whole structure again (then only the region the 2D sources
// change is smoothed). The key holds everything the stage reads, as exact bits: a hit
// gives the same bits as a build.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/geometry/surface_metric.h"
#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {
namespace surface_mesher {

struct CurvatureStage {
  std::unique_ptr<AdaptiveControlSpace> space;        // a working copy of the stage; null: not stored
  std::shared_ptr<const AdaptiveControlSpace> stage;  // the stage as stored (read only)
  long long evaluations = 0;                          // curvature evaluations the stage made (for the report)
};

// The key of the stage, or "" when the surface has no identity (then nothing is kept).
std::string curvatureStageKey(const Surface& surface, const SurfaceMetricOptions& sizing,
                              const std::vector<Source3D>& sources3d, const QuadtreeOptions& quadtree,
                              double refineThreshold, std::int64_t maxNodes, double gradation);
// Appends the exact bits of segment sources (the contour curvature sources) to a key.
void appendSourceBits(std::string& key, const std::vector<MetricSource>& sources);
// A copy of the stage stored under key (limits cleared: the caller sets its own), if any:
// made in the storage a finished run gave back (recycleCurvatureStage()) when there is one.
CurvatureStage findCurvatureStage(const std::string& key);
// Keeps a copy of cs (without its limits' progress callback) under key; the last few keys
// only. Returns the stored copy.
std::shared_ptr<const AdaptiveControlSpace> storeCurvatureStage(const std::string& key, const AdaptiveControlSpace& cs,
                                                                long long evaluations);
// Gives back a working copy of the stage under key that a run is done with: the next
// findCurvatureStage(key) copies the stage into its storage instead of fresh memory (a
// drag's copies then stay in memory already in use). Dropped when key is no longer kept.
void recycleCurvatureStage(const std::string& key, std::unique_ptr<AdaptiveControlSpace> space);

}  // namespace surface_mesher
}  // namespace anisomesh

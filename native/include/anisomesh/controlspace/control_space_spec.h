#pragma once
// A control space described by plain data, for the wasm bindings and the JSON case
// format: buildControlSpace(spec) runs the whole construction of section 2:
//   1. the structure (quadtree or background mesh) over `box`;
//   2. discrete `sources` (section 2.2: refine near them, weighted average, extrapolation);
//   3. the `analytic` metric function, if any (section 2.3: intersected at every node,
//      then elements split while metrics differ by more than `refineThreshold`);
//      with neither sources nor function, every node takes `defaultMetric`;
//   4. sizes clamped to [hmin, hmax];
//   5. gradation smoothing with ratio `gradation` (section 2.5; 0 = off, else >= 1).
// Errors: InvalidDomain (box), InvalidArgument (levels, gradation in (0, 1), clamps,
// negative radius...), ZeroLengthCurve, InvalidMetric (from Metric).
#include <memory>
#include <optional>
#include <vector>

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/controlspace/background_mesh_control_space.h"
#include "anisomesh/controlspace/metric_sources.h"
#include "anisomesh/controlspace/quadtree_control_space.h"

namespace anisomesh {

enum class ControlSpaceKind { Quadtree, BackgroundMesh };

struct ControlSpaceSpec {
  ControlSpaceKind kind = ControlSpaceKind::Quadtree;
  Box2 box{{0.0, 0.0}, {1.0, 1.0}};
  QuadtreeInterpolation interpolation = QuadtreeInterpolation::Bilinear;  // quadtree only
  BackgroundInterpolation backgroundInterpolation = BackgroundInterpolation::InverseSquaredDistance;
  int initialLevel = 2;           // quadtree: 2^initialLevel cells per side; background: grid 2^initialLevel
  int maxLevel = 14;              // deepest refinement
  double refineThreshold = 0.05;  // difference() that splits an element (continuous sources)
  double gradation = 0.0;         // dr; 0 = no smoothing
  std::vector<MetricSource> sources;
  MetricFunction analytic;          // empty = none
  bool analyticConcurrent = false;  // analytic may be called from several threads at once
  // > 0: continuous insertion leaves elements smaller than this times the smallest size
  // requested at their nodes unsplit (their interpolation error is below one mesh edge).
  double refineMinMetricSize = 0.0;
  // When set: continuous insertion splits only elements whose box it accepts (the region
  // the mesher will query); elsewhere the structure stays coarse.
  std::function<bool(const Box2&)> analyticDomain;
  std::optional<Metric> defaultMetric;  // when no source/function: default isotropic(box diagonal / 10)
  double hmin = 0.0;                    // 0 = no lower clamp
  double hmax = 0.0;                    // 0 = no upper clamp
  double cacheTolerance = 0.0;          // > 0: buildControlSpace wraps the result in a CachedControlSpace
  ControlSpaceLimits limits;            // node budget and progress of the construction (kept by the result)
};

// Builds the adaptive structure described by spec (steps 1-5 above).
std::unique_ptr<AdaptiveControlSpace> buildAdaptiveControlSpace(const ControlSpaceSpec& spec);

// Same, as the abstract ControlSpace the mesher takes; wrapped in a (not thread-safe)
// CachedControlSpace when spec.cacheTolerance > 0.
std::unique_ptr<ControlSpace> buildControlSpace(const ControlSpaceSpec& spec);

}  // namespace anisomesh

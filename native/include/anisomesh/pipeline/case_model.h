#pragma once
// The case model: what a JSON case describes, as plain structs (read by io/case_json.h,
// run by pipeline/). A planar case (examples/CASE_FORMAT.md): the domain's curves, the
// control space settings, the metric sources and the meshing options; a surface case
// (examples/SURFACE_FORMAT.md): a model of trimmed patches and the surface meshing options.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anisomesh/boundary/boundary_updates.h"
#include "anisomesh/controlspace/metric_sources.h"
#include "anisomesh/geometry/domain.h"
#include "anisomesh/metric/metric.h"
#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {

// "controlSpace": the settings of the control structure.
struct CaseControlSpaceSpec {
  std::string kind = "quadtree";    // "quadtree" | "background"
  double hmin = 0.0;                // smallest allowed size (0: no clamp)
  double hmax = 1.0;                // largest size, also the default metric
  std::optional<double> gradation;  // dr >= 1, or none (no smoothing)
  // quadtree: "bilinear" | "serendipity"; background: "linear" (barycentric, the default
  // for background) | "inverse_distance" (paper eq. 11); "bilinear" means the default of the kind.
  std::string interpolation = "bilinear";
  double refineThreshold = 0.1;  // difference() that splits a control element (analytic fields)
  int maxLevel = 0;              // deepest refinement; 0 = from hmin (box side / 2^L <= hmin), at most 14
  // Section 4 query cache: > 0 reuses the last metric for a query point within this
  // metric-space distance of the last query point (discretization and meshing); 0: off.
  double queryCache = 0.0;
};

enum class SourceType { Radial, Segment, Polyline, Curve, Nodes, Analytic };

// A named analytic metric field and its parameters (unused ones stay 0).
struct AnalyticFieldSpec {
  std::string field;        // "boundary_layer" | "shear_layer_circle" | "point" | "expression"
  Vec2 p1{0, 0}, p2{0, 0};  // boundary_layer: the wall line through p1, p2
  Vec2 center{0, 0};        // shear_layer_circle, point
  double radius = 0.0;      // shear_layer_circle
  double h0 = 0.0;          // size across the layer at the wall / circle, or at the point
  double hTangent = 0.0;    // size along the layer (boundary_layer, shear_layer_circle)
  double thickness = 0.0;   // distance over which the normal size grows from h0 to hTangent
  double growth = 0.0;      // point: size slope with distance, h(d) = h0 + growth d
  // expression: formulas in x, y for (alpha, h1, h2), already checked by the parser.
  std::string alpha = "0", h1, h2;
  std::string path;  // JSON path of the source, for evaluation errors
};

// One entry of "sources".
struct SourceSpec {
  SourceType type = SourceType::Radial;
  Vec2 center{0, 0};                 // radial
  Vec2 p1{0, 0}, p2{0, 0};           // segment
  std::vector<Vec2> points;          // polyline, nodes
  CurvePtr curve;                    // curve: c(t), t in [t1, t2] (section 2.2)
  double t1 = 0.0, t2 = 1.0;         // curve
  MetricSizes metric;                // radial, segment, polyline, curve: (alpha, h1, h2)
  std::vector<MetricSizes> metrics;  // nodes: one per point
  double radius = 0.0;               // radial, segment, polyline, curve: influence radius
  AnalyticFieldSpec analytic;
};

// "options": meshing options.
struct CaseOptions {
  bool quads = false;
  bool allQuads = false;
  std::int64_t maxElements = 50000000;
  std::int64_t maxControlNodes = 0;  // control-space node budget; 0: controlSpaceNodeBudget(maxElements)
};

struct CaseSpec {
  Domain domain;
  CaseControlSpaceSpec controlSpace;
  std::vector<SourceSpec> sources;
  CaseOptions options;
  BoundaryUpdateOptions boundary;  // "boundary": the section 3.2 thresholds (the paper's by default)
};

// A surface case.
struct SurfaceCaseSpec {
  SurfaceModel model;
  SurfaceMeshOptions options;
};

// The discrete sources among sources (radial, segment, polyline, nodes) as MetricSources,
// in their order; analytic fields are left out (see caseAnalyticMetric).
std::vector<MetricSource> discreteSources(const std::vector<SourceSpec>& sources);

}  // namespace anisomesh

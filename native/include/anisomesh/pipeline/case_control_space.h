#pragma once
// The control space of a JSON case: the paper's adaptive structure (quadtree or
// background mesh, section 2) built from the case's settings and sources.
//
// Construction order (why not everything through ControlSpaceSpec::sources):
// buildAdaptiveControlSpace inserts discrete sources first and extrapolates them into
// every node no source reached (fig. 2c), which would spread a fine radial source over
// the whole domain and lose the case's hmax default. So the structure is built by
// buildAdaptiveControlSpace with the continuous part only (hmax default intersected with
// every analytic field, section 2.3); then the discrete sources are inserted into the
// already initialized nodes (intersected, section 2.2), then sizes are clamped to
// [hmin, hmax] and smoothed with the gradation ratio dr (section 2.5).
#include <functional>
#include <memory>
#include <vector>

#include "anisomesh/controlspace/control_space_spec.h"
#include "anisomesh/pipeline/case_model.h"

namespace anisomesh {

// The continuous part of a case: isotropic hmax intersected with every analytic field
// (each field where it acts), sizes clamped to hmin. No discrete source, no gradation.
// Evaluation errors of expression fields (size <= 0, NaN) throw InvalidMetric naming the source.
MetricFunction caseAnalyticMetric(const CaseSpec& spec);

// The discrete sources of a case (radial, segment, polyline, nodes) as MetricSources.
std::vector<MetricSource> caseDiscreteSources(const CaseSpec& spec);

// The ControlSpaceSpec of the structure: kind, interpolation, box = domain bounds
// enlarged by 1% of the diagonal, analytic = caseAnalyticMetric; no sources, no clamps,
// no gradation (applied afterwards, see the header comment).
ControlSpaceSpec caseControlSpaceSpec(const CaseSpec& spec);

// Builds the case's adaptive control space (see the header comment) within the case's
// node budget (options.maxControlNodes, or derived from options.maxElements); progress,
// when given, is called during refinement and cancels it by returning false.
std::unique_ptr<AdaptiveControlSpace> buildCaseControlSpace(const CaseSpec& spec,
                                                            const std::function<bool(double)>& progress = {});

// Section 3.2 updates: intersects more discrete sources into cs, then clamps and smooths
// again with the case's settings (clamping and smoothing only ever make sizes smaller
// where needed, so repeated updates are consistent).
void addCaseSources(AdaptiveControlSpace& cs, const CaseSpec& spec, const std::vector<MetricSource>& sources);

// Clamps to [hmin, hmax] and smooths with the case's gradation (no-op parts when unset).
void finishCaseControlSpace(AdaptiveControlSpace& cs, const CaseSpec& spec);

}  // namespace anisomesh

#pragma once
// The control space of a JSON case, for now an analytic one (the quadtree / background
// structures replace it later): the intersection of the hmax background, every discrete
// source and every analytic field, clamped to hmin.
#include <memory>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/controlspace/control_space_algorithms.h"  // gradationSlope
#include "anisomesh/io/case_json.h"

namespace anisomesh {

// The metric one source asks for at p, or false when it does not reach p (outside its
// radius and no gradation). slope < 0 means no gradation.
bool sourceMetricAt(const SourceSpec& source, const Vec2& p, double slope, Metric* out);

// The case's metric function (captures a copy of what it needs from spec).
MetricFunction caseMetricFunction(const CaseSpec& spec);

// The control space of a case over the domain's bounding box (slightly enlarged).
std::unique_ptr<ControlSpace> buildCaseControlSpace(const CaseSpec& spec);

}  // namespace anisomesh

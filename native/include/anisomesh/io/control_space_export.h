#pragma once
// Inspection of control spaces (for the demo page and ParaView): control nodes with their
// metrics, and the structure's elements (quadtree leaves or background triangles).
#include <string>

#include <nlohmann/json.hpp>

#include "anisomesh/controlspace/adaptive_control_space.h"

namespace anisomesh {

// JSON: {"kind", "bounds": {"lo": [x, y], "hi": [x, y]}, "nodes": [{"p": [x, y],
// "m": [m11, m12, m22] (tensor M), "alpha", "h1", "h2", "free"}], "cells": [[node ids]]
// (leaf corners counter-clockwise, or triangles), and for a quadtree "boxes":
// [[xlo, ylo, xhi, yhi]] and "levels"}.
nlohmann::json controlSpaceToJson(const AdaptiveControlSpace& cs);

// The same as legacy VTK text (UNSTRUCTURED_GRID: quads or triangles, per-point 3x3
// TENSORS "metric" with the 2x2 M in the upper-left block, SCALARS h1, h2, alpha).
std::string controlSpaceToVtk(const AdaptiveControlSpace& cs);

// Writes controlSpaceToVtk to path; throws IoError when the file cannot be written.
void writeControlSpaceVtk(const AdaptiveControlSpace& cs, const std::string& path);

// Any control space sampled on an nx x ny grid of its bounds (e.g. an analytic one):
// {"bounds", "nx", "ny", "samples": [{"p", "m", "alpha", "h1", "h2"}]} row by row.
// Throws InvalidArgument unless nx, ny >= 1.
nlohmann::json sampledControlSpaceToJson(const ControlSpace& cs, int nx, int ny);

}  // namespace anisomesh

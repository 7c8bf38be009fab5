#pragma once
// Parameters of a merged surface mesh per patch: the merged mesh keeps one (u, v) per
// vertex (that of the first patch that placed it), so a vertex on a shared curve carries
// the other patch's parameters. Drawing each patch in its own (u, v) plane needs the
// parameters every element corner has in its element's patch.
#include <vector>

#include "anisomesh/mesh/mesh.h"
#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {

struct PatchParamsOptions {
  int samplesPerCurve = 64;  // coarse search along each contour curve before refinement
  int refineSteps = 40;      // golden-section steps on the best sample's neighbourhood
};

// Patch index of every element (triangles, then quads), from triangleRefs / quadRefs and
// the patches' ids (an id no patch has gives -1).
std::vector<int> elementPatches(const SurfaceModel& model, const Mesh& mesh);

// (u, v) of every element corner in its element's patch (triangles, 3 each, then quads,
// 4 each). A vertex placed by another patch lies on a contour of this one (a shared
// curve): its parameters are the contour point closest to it in 3D.
std::vector<Vec2> patchCornerParams(const SurfaceModel& model, const Mesh& mesh,
                                    const PatchParamsOptions& options = {});

}  // namespace anisomesh

// The Algorithm 1 driver shared by planar and surface cases.
#include "anisomesh/pipeline/algorithm1.h"

namespace anisomesh {

Mesh runAlgorithm1(Algorithm1Steps& steps, const BoundaryUpdateOptions& options, Algorithm1Report* report) {
  Algorithm1Report local;
  Algorithm1Report& r = report ? *report : local;
  steps.buildControlSpaces();
  for (int round = 0;; ++round) {
    steps.discretizeInvalidContours(round);
    r.rounds = round + 1;
    if (!options.enabled) break;
    if (round >= options.maxRounds) {
      r.converged = false;
      r.note = "section 3.2 updates stopped after " + std::to_string(options.maxRounds) + " rounds";
      break;
    }
    const bool changed = steps.checkBoundaries(round);
    // An invalid contour discretized in this very control space would come out the same
    // (e.g. curves shorter than half a size): only a change makes another round useful.
    if (!changed && !steps.hasStaleInvalidContour()) break;
  }
  return steps.meshPatches();
}

}  // namespace anisomesh

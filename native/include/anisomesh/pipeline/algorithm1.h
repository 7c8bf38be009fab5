#pragma once
// The paper's Algorithm 1, one driver for every case: a planar case is one patch on the
// plane, a surface case a model of patches. The case supplies the steps; the driver runs
// them in the paper's order and owns the section 3.2 loop's rule for going on.
#include <string>

#include "anisomesh/boundary/boundary_updates.h"
#include "anisomesh/mesh/mesh.h"

namespace anisomesh {

// The steps of Algorithm 1 a kind of case provides (pipeline.cpp: planar; surface/: models).
class Algorithm1Steps {
 public:
  Algorithm1Steps() = default;
  Algorithm1Steps(const Algorithm1Steps&) = delete;
  Algorithm1Steps& operator=(const Algorithm1Steps&) = delete;
  virtual ~Algorithm1Steps() = default;
  // Steps 1-2: the initial control space of every patch; every contour invalid.
  virtual void buildControlSpaces() = 0;
  // Step 4: discretizes the invalid contours (all of them in round 0; surfaces then adapt
  // the control spaces of patches across their shared contours).
  virtual void discretizeInvalidContours(int round) = 0;
  // Steps 5-12: boundary-only triangulation and the section 3.2 checks of each patch whose
  // boundary or control space changed; updates the control spaces and marks contours
  // invalid. Returns whether a control space changed.
  virtual bool checkBoundaries(int round) = 0;
  // A contour is marked invalid that was not discretized in the current control space (so
  // another round can change it).
  virtual bool hasStaleInvalidContour() const = 0;
  // Steps 14-16: inner nodes and improvement in every patch (and quads), merged.
  virtual Mesh meshPatches() = 0;
};

struct Algorithm1Report {
  int rounds = 0;         // discretization rounds of the section 3.2 loop
  bool converged = true;  // false: the loop stopped at options.maxRounds
  std::string note;       // why it stopped early, when it did
};

// Runs the steps: control spaces, then rounds of (discretize invalid contours, check and
// update) until no control space changed and no stale contour is invalid, or maxRounds
// rounds of checks (options.enabled false: one discretization, no checks); then the patches.
Mesh runAlgorithm1(Algorithm1Steps& steps, const BoundaryUpdateOptions& options, Algorithm1Report* report = nullptr);

}  // namespace anisomesh

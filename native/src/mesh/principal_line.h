#pragma once
// Private to mesh/: lines of a control space's principal directions. Domain decomposition
// cuts a curved anisotropic layer along them, since a straight cut meets such a layer
// obliquely and an oblique part boundary costs quality next to it.
#include <functional>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/core/types.h"

namespace anisomesh {
namespace mesh_internal {

struct PrincipalLineOptions {
  double step = 0.0;             // physical length of one integration step
  int maxSteps = 1024;           // per direction: a line still inside after this many is given up
  double isotropicAspect = 1.5;  // below this aspect ratio the line keeps its direction (blended above 1)
};

// Where the step [p, q] leaves the region: true with the parameter t along [p, q] of the
// first crossing and the id of what it crosses.
using RegionExit = std::function<bool(const Vec2& p, const Vec2& q, double& t, int& id)>;

struct PrincipalLine {
  std::vector<Vec2> points;  // from one exit to the other (both exit points included)
  int firstExit = -1, lastExit = -1;
};

// The line through seed that follows, at every point, the principal direction of the
// metric closest to its current direction, starting along the one closest to 'along';
// traced both ways with the midpoint rule until it leaves the region. Empty points when it
// did not leave within maxSteps or met a metric that is not finite.
PrincipalLine tracePrincipalLine(const ControlSpace& cs, const Vec2& seed, const Vec2& along, const RegionExit& exit,
                                 const PrincipalLineOptions& options);

}  // namespace mesh_internal
}  // namespace anisomesh

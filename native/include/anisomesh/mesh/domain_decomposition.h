#pragma once
// Planar domain decomposition for the mesher (as ParMMG splits work for MMG, on one
// machine): the domain is bisected recursively at the median of its metric area by
// straight cuts whose chords join boundary points, or, where no straight cut runs along
// or across the stretching (a curved layer), by a cut along a line of the metric's
// principal directions; each chord is discretized once at unit metric length. The parts
// are meshed independently (in parallel when threads allow) and merged into one
// conforming mesh, since neighbouring parts share the chords' points and the mesher never
// splits or moves a boundary edge.
//
// The decomposition depends on the loops and the control space only, never on the thread
// count: the same mesh for any number of threads. A cut is kept only when every chord is
// valid (inside the part, crossing no edge or other chord, not sharing an end point, at
// least minChordAngle from the boundary at its ends, within 2 degrees of a principal
// direction wherever the metric's aspect ratio exceeds 1.5), else nearby cut positions
// are tried and then the part stays whole.
#include <cstdint>
#include <vector>

#include "anisomesh/controlspace/control_space.h"
#include "anisomesh/geometry/boundary_loop.h"
#include "anisomesh/mesh/mesh.h"
#include "anisomesh/mesh/planar_mesher.h"

namespace anisomesh {

struct DomainDecompositionOptions {
  std::int64_t partElements = 15000;  // aim: parts of at least this many elements
  int maxParts = 64;                  // at most this many parts (a power of 2)
  int gridSide = 128;                 // metric-area samples along the cut axis (a quarter across)
  double minChordAngle = 0.7;         // radians (metric): chords closer to a boundary edge at their ends are rejected
};

// One part: loops of global point ids, the outer one counter-clockwise first, then its
// holes clockwise; edgeRefs[l][i] is the reference of edge i of loop l (chords: 0) and
// chord[l][i] is 1 for a chord edge.
struct DomainPart {
  std::vector<std::vector<int>> loops;
  std::vector<std::vector<int>> edgeRefs;
  std::vector<std::vector<char>> chord;
};

struct DomainParts {
  std::vector<Vec2> points;  // the loops' points (loop by loop), then the chords' inner points
  int loopPoints = 0;        // how many of points are the input loops' points
  std::vector<DomainPart> parts;
  double estimatedElements = 0.0;  // from the metric area samples of the whole domain
};

// Splits the region inside loops[0] and outside loops[1..] into parts; one part (the
// loops themselves) when the domain is too small for options.partElements or no valid cut is found.
DomainParts decomposeDomain(const std::vector<BoundaryLoop>& loops, const ControlSpace& cs,
                            const DomainDecompositionOptions& options = {});

// Meshes every part with the planar mesher (concurrently when cs answers concurrent
// queries and threads are set) and merges them: the loops' points first (unchanged), then
// the chords' points, then each part's inner points in part order; boundary edges are the
// loops' edges in input order. Timings are summed over the parts (CPU seconds).
Mesh meshDomainParts(const std::vector<BoundaryLoop>& loops, const DomainParts& parts, const ControlSpace& cs,
                     const PlanarMesherOptions& options);

}  // namespace anisomesh

#pragma once
// Section 2.5.2 for the quadtree as the paper describes it: a recursive traversal in two
// steps, "upwards" from the leaves to the main level, then "downwards", in each step the
// nodes of every tree element adjusted with the nodes of its sub-elements by the pairwise
// rule (eqs. 3-9). smoothGradation() (control_space_algorithms.h) is the work-set
// alternative; docs/paper_rules.md compares the two (bound reached, node updates, time).
#include "anisomesh/controlspace/quadtree_control_space.h"

namespace anisomesh {

struct TreeGradationOptions {
  double ratio = 2.0;        // dr >= 1: largest ratio of neighbouring element sizes
  double tolerance = 1e-10;  // relative change below which limitGradation() leaves a node
  int passes = 1;            // up/down pairs (the paper: 1)
};

// Upward pass (post-order: children before their parent), for every internal cell the
// pairwise rule both ways between every two distinct nodes of its four children; at the
// main level the same between the corner nodes of edge-neighbouring main cells (one
// sweep forward, one backward); then the downward pass (pre-order: a cell before its
// children). Only free nodes change; hanging nodes follow their masters at the end
// (applyConstraints). Returns the number of node updates. Throws InvalidArgument for
// dr < 1 or passes < 1.
int smoothGradationUpDown(QuadtreeControlSpace& cs, const TreeGradationOptions& options = {});

}  // namespace anisomesh

#pragma once
// Building and combining adaptive control spaces (sections 2.2-2.5). Every function works
// on both structures through AdaptiveControlSpace, and leaves the structure valid
// (quadtree balanced, hanging nodes consistent) when it returns.
#include <optional>
#include <vector>

#include "anisomesh/controlspace/adaptive_control_space.h"
#include "anisomesh/controlspace/metric_sources.h"

namespace anisomesh {

struct DiscreteInsertionOptions {
  SourceOptions source;  // element size required near each source
  // Metric of every node when no node at all is reached (default: isotropic, size of
  // the box diagonal / 4).
  std::optional<Metric> fallbackMetric;
};

// Discrete sources (section 2.2, fig. 2): (a) refine elements within r of a source down
// to the source's target size max(r, h_min(M)); (b) every free node within r + target of
// sources takes their weighted average (weight 1/(max(d - r, 0) + target/4)^2: equal
// inside the regions, decaying outside) - intersected with its current metric when the
// node was already initialized; (c) extrapolate into nodes no source reached.
// Sources entirely outside the box (farther than r) are ignored: all outside = no-op.
void insertSources(AdaptiveControlSpace& cs, const std::vector<MetricSource>& sources,
                   const DiscreteInsertionOptions& options = {});

// Splits elements whose nodes hold metrics differing (difference() between any two) by
// more than threshold, recursively down to the minimum element size; new nodes take the
// interpolated metric. Returns the number of elements added.
int refineWhereMetricsDiffer(AdaptiveControlSpace& cs, double threshold);

// Iteratively fills uninitialized free nodes, front by front along controlEdges(), with
// the inverse-squared-distance average of their initialized neighbours (fig. 2c); nodes
// unreachable (or all, when none is initialized) get fallback. Returns the count filled.
int extrapolateMetric(AdaptiveControlSpace& cs, const Metric& fallback);

struct ContinuousInsertionOptions {
  double threshold = 0.05;        // difference() between an element's nodes that splits it
  bool checkSamples = true;       // also compare interpolated and analytic metric inside elements
  double sampleThreshold = -1.0;  // difference() at samples that splits (< 0: same as threshold)
  // > 0: elements whose longest side is below minMetricSize times the smallest size at
  // their nodes are not split (the mesher cannot see variation below its edge length).
  double minMetricSize = 0.0;
  // f (and domain) may be called from several threads: new nodes are evaluated and, on a
  // fresh structure, elements judged for splitting in parallel (the same result).
  bool concurrent = false;
  // When set: elements whose bounding box it rejects (outside the region the mesher will
  // query, e.g. the carrier of a remesh) are not split.
  std::function<bool(const Box2&)> domain;
};

// Continuous source (section 2.3): every free node takes f (intersected with its metric
// when already initialized); then elements are split recursively while their nodes'
// metrics differ by more than threshold, or (checkSamples) the interpolated metric at
// interior sample points differs from the analytic one by more than sampleThreshold
// (down to the minimum size). The node test is the paper's; the sample test is what
// bounds the interpolation error (and catches features between nodes).
void insertMetricFunction(AdaptiveControlSpace& cs, const MetricFunction& f,
                          const ContinuousInsertionOptions& options = {});

struct MinimumOptions {
  double threshold = 0.02;  // phase 2 refinement threshold on difference()
  // Phase 3: shrink the nodes of elements whose interpolation exceeds the exact minimum
  // at sample points, so that the result errs on the fine side (false: exact at nodes
  // only, as in the paper).
  bool conservative = true;
};

// Minimum of two control spaces (section 2.4), result in cs1: (1) every node of cs1 takes
// min(M_cs1, M_cs2(P)); (2) the nodes of cs2 act as discrete sources: cs1's elements
// containing a node P_k of cs2 are split (not below cs2's element size at P_k) while
// the result at P_k differs from min(M_cs1_original(P_k), M_k) by more than threshold,
// new nodes taking min(M_cs1_original, M_cs2) directly; (3) phase 1 again, then (our
// reading of "where the minimum is not represented well", when conservative) every
// element is checked at 16 (leaf) or 13 (triangle) interior points against the exact
// minimum, and where its interpolation is larger by a factor 1 + e its free nodes are
// scaled down by 1 + e (the largest over their elements; up to 3 passes).
//
// Exactness between nodes is impossible for an interpolated structure: the minimum of
// two interpolated fields is not one (it has kinks where the smaller input changes, the
// background mesh's inverse-distance interpolation jumps across its edges, and
// intersect() is not linear in Mt), and refining does not remove that (new nodes copy
// the inputs' own interpolation error, and the kinks stay at every depth). So phase 3
// errs on the fine side instead: the result is inside the exact minimum at the samples
// and close to it between them. MinimumControlSpace (minimum_control_space.h) is the
// exact minimum at every point, evaluated lazily.
void intersectControlSpace(AdaptiveControlSpace& cs1, const ControlSpace& cs2, const std::vector<ControlNode>& cs2Nodes,
                           const MinimumOptions& options = {});
// Same, taking cs2's nodes from the structure itself.
void intersectControlSpace(AdaptiveControlSpace& cs1, const AdaptiveControlSpace& cs2,
                           const MinimumOptions& options = {});

struct GradationOptions {
  double ratio = 2.0;        // dr >= 1: largest ratio of neighbouring element sizes
  double tolerance = 1e-10;  // relative change below which a node is not re-queued
  // Also enforce the bound on edges at hanging nodes (quadtree) by shrinking their
  // masters; false = only edges between free nodes (controlEdges()), faster.
  bool throughHangingNodes = true;
};

// a_max = 2 (dr - 1) / (dr + 1) (eq. 4): slope of the requested length when consecutive
// elements grow by the factor dr. Throws InvalidArgument unless dr >= 1 (finite).
double gradationSlope(double ratio);

// Pairwise rule (eqs. 3-9) applied one way: mj = min(mj, s mi) with s = 1 + a_max d / h_i
// (eq. 7 at the binding value a = a_max), h_i the size of mi along pj - pi. Afterwards the
// size of mj along the edge is at most h_i + a_max d. Intersection keeps anisotropy.
// Returns true when mj changed by more than tolerance (relative).
bool limitGradation(const Metric& mi, const Vec2& pi, Metric& mj, const Vec2& pj, double slope,
                    double tolerance = 1e-12);

// Global smoothing (section 2.5.2) with a work-set: all nodes start in the set; the node
// with the smallest requested size is taken first (Dijkstra-like order, so most nodes
// are final when taken) and limits each neighbour along the structure's side edges; a
// neighbour that changed is re-queued. Tensors only grow (Loewner order: sizes only
// shrink) and stay below the finest metric present, so with the tolerance it terminates; at the end every
// edge satisfies h_j <= h_i + a_max d. Quadtree hanging nodes cannot change on their
// own: see throughHangingNodes and the comment in the implementation. Returns the
// number of node updates. Throws InvalidArgument for dr < 1.
int smoothGradation(AdaptiveControlSpace& cs, const GradationOptions& options = {});

// smoothGradation() of a control space that held the bound (smoothGradation() left it so)
// until the nodes `changed` (AdaptiveControlSpace::nodesChangedSince(): values, flags, new
// nodes) changed: the work-set starts from those nodes and their neighbours only. An edge
// between two unchanged nodes still holds the bound, so a node the full work-set would take
// and this one does not limits nothing: the nodes that act are taken in the same (key,
// index) order, and the result is the one smoothGradation() gives to its own idempotence
// (~1e-9 relative: smoothing a smooth space again moves some nodes that much; and not where
// its hanging-node rounds hit their cap), at the cost of the changed region only (but the
// edge graph of the whole structure is still built).
int resmoothGradation(AdaptiveControlSpace& cs, const std::vector<int>& changed, const GradationOptions& options = {});

// The metric with the same directions and sizes clamped to [hmin, hmax].
Metric clampMetricSizes(const Metric& m, double hmin, double hmax);
// Clamps every free node's sizes to [hmin, hmax] (0 < hmin <= hmax, hmax may be infinite).
void clampSizes(AdaptiveControlSpace& cs, double hmin, double hmax);

}  // namespace anisomesh

#pragma once
// Private header of the surface mesher (paper section 3, Algorithm 1, on a model of
// patches): the per-run state (ModelMesher) and the helpers its operation files share.
// Driver: surface_mesh.cpp; patch control spaces: patch_control_space.cpp; shared curves
// and contour discretization: shared_curves.cpp; section 3.2 boundary checks:
// boundary_checks.cpp; merging of the patch meshes: merging.cpp; 3D quality measures:
// surface_quality.cpp.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>

#include "anisomesh/boundary/discretize.h"
#include "anisomesh/controlspace/control_space_algorithms.h"
#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/clock.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/parallel.h"
#include "anisomesh/core/portable_math.h"
#include "anisomesh/pipeline/algorithm1.h"
#include "anisomesh/surface/surface_mesh.h"

namespace anisomesh {
namespace surface_mesher {

inline std::string fmt(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

inline std::string fmtUv(const Vec2& p) { return "(u, v) = (" + fmt(p.x()) + ", " + fmt(p.y()) + ")"; }

inline std::string patchLabel(const SurfacePatch& p, int index) {
  return "patch '" + (p.name.empty() ? std::to_string(index) : p.name) + "'";
}

// One thread's tally of control-space queries and curvature evaluations (a cache line of
// its own: threads that count side by side do not share one).
struct alignas(64) QueryTally {
  long long queries = 0;
  double seconds = 0.0;
  long long curvature = 0;
  double curvatureSeconds = 0.0;
};

// Cost counters shared by every patch of one run. They are tallied per thread slot
// (core/parallel.h), so patches, parts and curvature samples evaluated concurrently count
// without atomics; the totals are sums, the same for any thread count.
struct Counters {
  std::array<QueryTally, kThreadSlots> tallies{};
  // The calling thread's tally.
  QueryTally& mine() { return tallies[size_t(threadSlot())]; }
  // The control-space queries of every thread.
  long long queries() const { return sum(&QueryTally::queries); }
  // Their sampled time, seconds.
  double querySeconds() const { return sum(&QueryTally::seconds); }
  // The curvature evaluations of every thread.
  long long curvature() const { return sum(&QueryTally::curvature); }
  // Their sampled time, seconds.
  double curvatureSeconds() const { return sum(&QueryTally::curvatureSeconds); }

 private:
  template <class T>
  T sum(T QueryTally::*field) const {
    T total = 0;
    for (const QueryTally& t : tallies) total += t.*field;
    return total;
  }
};

// Counts (and times) the queries the discretization and the mesher make; Mp comes from
// the inner space when it keeps one (section 4.3 view), else from the surface itself.
class CountingControlSpace : public ControlSpace {
 public:
  CountingControlSpace(const ControlSpace& inner, const Surface& s, Counters& c, bool innerHasMp)
      : inner_(inner), s_(s), c_(c), innerHasMp_(innerHasMp) {}
  // The time is sampled: one query in 32 is timed and counted 32 times (reading the clock
  // at every query cost 7% of a surface run, as much as a cheap query itself).
  Metric metricAt(const Vec2& p) const override {
    QueryTally& t = c_.mine();
    if ((t.queries++ & 31) != 0) return inner_.metricAt(p);
    const auto t0 = Clock::now();
    Metric m = inner_.metricAt(p);
    t.seconds += 32.0 * secondsSince(t0);
    return m;
  }
  Mat2 parameterizationAt(const Vec2& p) const override {
    return innerHasMp_ ? inner_.parameterizationAt(p) : parameterizationMatrix(s_, p);
  }
  Box2 bounds() const override { return inner_.bounds(); }
  // As the inner space's (the tallies are per thread; the surface keeps no state).
  bool concurrentQueries() const override { return inner_.concurrentQueries(); }
  bool countsQueries() const override { return true; }

 private:
  const ControlSpace& inner_;
  const Surface& s_;
  Counters& c_;
  bool innerHasMp_;
};

inline const Contour& contourOf(const SurfacePatch& p, int k) {
  return k == 0 ? p.domain.outer : p.domain.holes[size_t(k - 1)];
}

inline int contourCount(const SurfacePatch& p) { return 1 + int(p.domain.holes.size()); }

// The curve a reference names, or nullptr when the model has no such patch, contour or curve.
inline const Curve* curveAt(const SurfaceModel& m, const CurveRef& r) {
  if (r.patch < 0 || size_t(r.patch) >= m.patches.size()) return nullptr;
  const SurfacePatch& p = m.patches[size_t(r.patch)];
  if (r.contour < 0 || r.contour >= contourCount(p)) return nullptr;
  const Contour& c = contourOf(p, r.contour);
  return r.curve >= 0 && size_t(r.curve) < c.curves.size() ? c.curves[size_t(r.curve)].curve.get() : nullptr;
}

// One boundary curve of one patch and its current discretization (own t ascending).
struct Slot {
  int patch = 0, contour = 0, curve = 0;
  CurvePtr c;
  int minSegments = 1;
  int master = -1;  // slot discretized with this one (the "a" side), or -1
  bool masterReversed = false;
  int follower = -1;      // the "b" side when this slot is a master
  std::vector<double> t;  // parameters, 0 ... 1
  std::vector<int> gid;   // merged-mesh vertex of each point
  bool invalid = true;
};

inline std::string slotName(const SurfaceModel& m, const Slot& s) {
  return patchLabel(m.patches[size_t(s.patch)], s.patch) + " " + contourName(s.contour) + " curve " +
         std::to_string(s.curve);
}

// 3D point of a slot's curve at t.
inline Vec3 slotPoint(const SurfaceModel& m, const Slot& s, double t) {
  return m.patches[size_t(s.patch)].surface->point(s.c->point(t));
}

// Everything one run keeps per patch.
struct PatchState {
  std::unique_ptr<AdaptiveControlSpace> cs;
  std::unique_ptr<ParameterizedControlSpace> parameterized;  // section 4.3 view (Stored, Computed)
  std::unique_ptr<CountingControlSpace> counted;
  std::vector<std::vector<int>> slots;  // per contour, per curve: slot index
  bool invalid = true;
  bool modified = false;
  std::string stageKey;  // the key of the curvature stage cs was copied from ("" when none)

  PatchState() = default;
  PatchState(PatchState&&) = default;
  PatchState& operator=(PatchState&&) = default;
  // Gives cs's storage back to the curvature-stage cache (the next drag copies into it).
  ~PatchState();
};

// A surface model as Algorithm 1 sees it (pipeline/algorithm1.h): the steps on every patch.
class ModelMesher final : public Algorithm1Steps {
 public:
  ModelMesher(const SurfaceModel& m, const SurfaceMeshOptions& o) : m_(m), o_(o) {}
  // Checks the model, then runs Algorithm 1 on it.
  Mesh run(SurfaceMeshReport* report);

  void buildControlSpaces() override;
  void discretizeInvalidContours(int round) override;
  bool checkBoundaries(int round) override;
  bool hasStaleInvalidContour() const override;
  Mesh meshPatches() override;
  // The patches' meshes in (u, v), one per patch, on loops (loopsOf of each patch).
  std::vector<Mesh> meshPatchInteriors(const std::vector<std::vector<BoundaryLoop>>& loops);

 private:
  void setupSlots();
  void validateSharing();
  void assignCornerIds();
  void discretize(int slot);
  std::vector<double> discretizeShared(const Slot& a, const Slot& b, std::vector<double>* tb);
  // Boundary loops of a patch with the merged-mesh id of every point and whether each edge lies on a shared curve.
  // With edgeMidpoints: each loop's edgeMidpoints, the (u, v) of the curve at the middle parameter of the edge.
  std::vector<BoundaryLoop> loopsOf(int patch, std::vector<int>* ids, std::vector<char>* sharedEdge,
                                    bool edgeMidpoints = false) const;
  void adaptAcrossShared();
  void checkPatchBoundary(int patch);
  // Queues a source for the patch's control space (inserted by flushSources()).
  template <class S>
  void addSource(int patch, const S& s) {
    pending_[size_t(patch)].emplace_back(std::in_place_type<S>, s);
  }
  void flushSources();
  // After patch's control space changed: its section 4.3 view and the counting wrapper.
  void refreshQueries(size_t patch);
  std::vector<ControlSpaceGlyph> glyphs() const;
  const ControlSpace& space(int patch) const { return *ps_[size_t(patch)].counted; }
  Vec2 uvOf(const Slot& s, size_t i) const { return s.c->point(s.t[i]); }

  const SurfaceModel& m_;
  SurfaceMeshOptions o_;
  std::shared_ptr<Counters> counters_ = std::make_shared<Counters>();  // (kept by DeferredMeasures)
  std::vector<Slot> slots_;
  std::vector<PatchState> ps_;
  std::vector<std::vector<MetricSource>> pending_;
  // Per patch: the boundary triangulation of its last check, for its meshing on the same loops.
  std::vector<std::shared_ptr<BoundaryTriangulationCache>> boundaryCaches_;
  int nextId_ = 0;
  int invalidations_ = 0;
  double size_ = 1.0;
  SurfaceMeshReport* report_ = nullptr;
  std::array<int, 3> updateCounts_{};  // section 3.2 sources: chord, proximity, short segment
};

// One patch's mesh as the 3D measures read it: its (u, v) points and elements (local
// indices, in the mesher's orientation) and each point's vertex in the merged mesh.
struct MeasuredPatch {
  std::shared_ptr<const Surface> surface;
  const ControlSpace* space = nullptr;  // the patch's counted control space (PatchState::counted)
  std::vector<Vec2> params;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 4>> quads;
  std::vector<int> gid;
};

// The 3D measures of one run (surface_measures.cpp): made at once, or kept
// (SurfaceMeshReport::deferred) with the patch states whose control spaces they query.
struct DeferredMeasures {
  std::vector<PatchState> states;  // deferred: owns what MeasuredPatch::space points to
  std::shared_ptr<Counters> counters;
  std::vector<MeasuredPatch> patches;
  std::vector<Vec3> points;  // merged-mesh points
  double chordTolerance = 0.0;
  double seconds = 0.0;  // time spent measuring
  bool elementsDone = false, chordsDone = false;
  Surface3DQuality q;
  std::vector<double> elementQuality;          // triangles (all patches), then quads
  std::vector<SurfaceEdgeLength> edgeLengths;  // distinct edges, in the order first met
  std::vector<std::array<int, 3>> edgeAt;      // each distinct edge's patch and local points
  // Per-element quality and per-edge length (every control-space query of the measures).
  void measureElements();
  // Chord deviations and inverted elements (surface evaluations only); measureElements() first.
  void measureChords();
  // Copies what is measured into the report.
  void fill(SurfaceMeshReport& report) const;
};

// The patch's control space; *stageKey (when given) takes the key of its kept curvature
// stage ("" when none is kept).
std::unique_ptr<AdaptiveControlSpace> buildControlSpaceImpl(const SurfacePatch& patch,
                                                            const std::vector<Source3D>& sources3d,
                                                            const SurfaceMeshOptions& o, Counters& counters,
                                                            std::string* stageKey = nullptr);

// The (u, v) shifts that map a patch onto itself across its periodic seams (curves of the
// patch shared with each other that differ by a constant shift): each period and, with two,
// their sums and differences; empty for a patch without one (seam_images.cpp).
std::vector<Vec2> seamShifts(const SurfaceModel& m, int patch);
// The sources and their copies moved by each shift: a source near a seam acts across it.
std::vector<MetricSource> withSeamImages(const std::vector<MetricSource>& sources, const std::vector<Vec2>& shifts);

double modelSize(const SurfaceModel& m);

// Gaps between an edge's chord x0x1 and the surface at 7 samples of its parameter segment
// u0u1: along the surface normal (normal), and as chordDeviation() measures them (iso).
struct EdgeChordGaps {
  double normal = 0.0, iso = 0.0;
};
EdgeChordGaps edgeChordGaps(const Surface& s, const Vec2& u0, const Vec2& u1, const Vec3& x0, const Vec3& x1);

// The same gap inside the triangle (u0, u1, u2) -> (x0, x1, x2): at the 10 interior
// barycentric points (i, j, k) / 6 (centroid included), the distance from the flat
// triangle's point to the tangent plane at the surface point of the same parameter.
double normalTriangleDeviation(const Surface& s, const Vec2 u[3], const Vec3 x[3]);

// 3D quad quality in a constant metric: min over corners of 2 |e1 x e2|_M / (|e1|_M^2 + |e2|_M^2)
// (1 for a unit square; as metricQuadQuality in the parameter plane).
double quadQuality3D(const Vec3 x[4], const Mat3& m3);

// Flips whole patches so that elements on both sides of every shared edge traverse it in
// opposite directions (one consistent 3D orientation), starting from the first patch of
// each connected group; a patch whose sharing contradicts itself (non-orientable) is left.
// patchTriangles / patchQuads: element counts per patch, in the order of out's lists.
void orientPatches(Mesh& out, const std::vector<int>& patchTriangles, const std::vector<int>& patchQuads,
                   const std::set<std::array<int, 2>>& shared);

}  // namespace surface_mesher
}  // namespace anisomesh

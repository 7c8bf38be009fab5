// Surface meshing: the cache of patch control spaces after their curvature stage (see
// curvature_stage_cache.h). A few entries (a drag touches one patch; two-patch cases
// have two), least recently used out first, behind a mutex (patches may be built on
// several threads).
#include "curvature_stage_cache.h"

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <mutex>
#include "anisomesh/core/error.h"
#include "anisomesh/core/number_text.h"

namespace anisomesh {
namespace surface_mesher {

namespace {

struct Entry {
  std::string key;
  std::shared_ptr<const AdaptiveControlSpace> space;
  std::unique_ptr<AdaptiveControlSpace> spare;  // storage a finished run gave back
  long long evaluations = 0;
  std::uint64_t used = 0;
};

constexpr size_t kEntries = 4;

struct Cache {
  std::mutex mutex;
  std::vector<Entry> entries;
  std::uint64_t clock = 0;
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

std::string curvatureStageKey(const Surface& surface, const SurfaceMetricOptions& sizing,
                              const std::vector<Source3D>& sources3d, const QuadtreeOptions& quadtree,
                              double refineThreshold, std::int64_t maxNodes, double gradation) {
  const std::string id = surface.identity();
  if (id.empty() || quadtree.initialMetric) return "";
  std::string key = id + "|";
  for (double x : {sizing.chordTolerance, sizing.angleTolerance, sizing.hmin, sizing.hmax, sizing.maxAspectRatio,
                   refineThreshold, gradation})
    appendDoubleBits(key, x);
  key += std::to_string(quadtree.initialLevel) + ' ' + std::to_string(quadtree.maxLevel) + ' ' +
         std::to_string(int(quadtree.interpolation)) + ' ' + std::to_string(maxNodes) + '|';
  for (const Source3D& s : sources3d) {
    for (int k = 0; k < 3; ++k) appendDoubleBits(key, s.center[k]);
    appendDoubleBits(key, s.h);
    appendDoubleBits(key, s.radius);
  }
  return key;
}

void appendSourceBits(std::string& key, const std::vector<MetricSource>& sources) {
  key += '|';
  for (const MetricSource& source : sources) {
    const auto* s = std::get_if<SegmentSource>(&source);
    require(s != nullptr, ErrorCode::Internal, "appendSourceBits: only segment sources have a key");
    const SymMt m = toSymMt(s->metric);
    for (double x : {s->a.x(), s->a.y(), s->b.x(), s->b.y(), m.a, m.b, m.c, s->radius}) appendDoubleBits(key, x);
  }
}

CurvatureStage findCurvatureStage(const std::string& key) {
  CurvatureStage out;
  if (key.empty()) return out;
  std::unique_ptr<AdaptiveControlSpace> spare;
  {
    Cache& c = cache();
    const std::lock_guard<std::mutex> lock(c.mutex);
    for (Entry& e : c.entries)
      if (e.key == key) {
        e.used = ++c.clock;
        out.stage = e.space;
        spare = std::move(e.spare);
        out.evaluations = e.evaluations;
        break;
      }
  }
  // The copy outside the lock (the stored stage is only read): patches on other threads
  // copy theirs meanwhile.
  if (out.stage) out.space = spare && spare->assignFrom(*out.stage) ? std::move(spare) : out.stage->clone();
  return out;
}

std::shared_ptr<const AdaptiveControlSpace> storeCurvatureStage(const std::string& key, const AdaptiveControlSpace& cs,
                                                                long long evaluations) {
  if (key.empty()) return nullptr;
  std::unique_ptr<AdaptiveControlSpace> copy = cs.clone();
  ControlSpaceLimits limits;
  limits.maxNodes = cs.limits().maxNodes;
  copy->setLimits(limits);  // the run's progress callback must not outlive it
  std::shared_ptr<const AdaptiveControlSpace> stored = std::move(copy);
  std::unique_ptr<AdaptiveControlSpace> dropped;  // (freed outside the lock)
  Cache& c = cache();
  const std::lock_guard<std::mutex> lock(c.mutex);
  Entry* slot = nullptr;
  for (Entry& e : c.entries)
    if (e.key == key) slot = &e;
  if (!slot && c.entries.size() < kEntries) slot = &c.entries.emplace_back();
  if (!slot) {
    slot = &c.entries.front();
    for (Entry& e : c.entries)
      if (e.used < slot->used) slot = &e;
  }
  if (slot->key != key) dropped = std::move(slot->spare);
  slot->key = key;
  slot->space = stored;
  slot->evaluations = evaluations;
  slot->used = ++c.clock;
  return stored;
}

void recycleCurvatureStage(const std::string& key, std::unique_ptr<AdaptiveControlSpace> space) {
  if (key.empty() || !space) return;
  Cache& c = cache();
  const std::lock_guard<std::mutex> lock(c.mutex);
  for (Entry& e : c.entries)
    if (e.key == key && !e.spare) {
      e.spare = std::move(space);
      return;
    }
}

}  // namespace surface_mesher
}  // namespace anisomesh

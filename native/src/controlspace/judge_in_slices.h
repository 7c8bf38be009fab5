#pragma once
// Private to controlspace/: the verdicts of a refinement round judged in parallel chunks, a
// slice of the round at a time, with the progress ticks (which may cancel the run) on the
// calling thread between slices, as one thread gives them per element.
#include <algorithm>
#include <cstddef>

#include "anisomesh/core/parallel.h"

namespace anisomesh {
namespace controlspace_internal {

// Calls judge(k) for every k < n, `slice` items at a time split into parallel chunks of at
// least `grain`; after each slice, tick() once per item of it on this thread.
template <class Judge, class Tick>
void judgeInSlices(size_t n, size_t slice, size_t grain, const Judge& judge, const Tick& tick) {
  for (size_t s0 = 0; s0 < n; s0 += slice) {
    const size_t m = std::min(slice, n - s0);
    parallelChunks(m, grain, [&](size_t, size_t b, size_t e) {
      for (size_t k = b; k < e; ++k) judge(s0 + k);
    });
    for (size_t k = 0; k < m; ++k) tick();
  }
}

}  // namespace controlspace_internal
}  // namespace anisomesh

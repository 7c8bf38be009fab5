#pragma once
// The clock the stage timings (reports, progress) are measured with.
#include <chrono>

namespace anisomesh {

using Clock = std::chrono::steady_clock;

// Wall seconds from t0 to now.
inline double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace anisomesh

#pragma once
// Double-to-integer conversions decided in double: a value out of the integer's range
// (huge, infinite or NaN, as hostile input makes) never reaches the conversion itself,
// which is undefined behaviour there (the sanitize build checks float-cast-overflow).
#include <cstdint>

namespace anisomesh {

// The cell index floor(t) of a uniform grid clamped to [0, n - 1] (n >= 1); NaN gives 0.
inline int clampedCell(double t, int n) {
  if (!(t >= 1.0)) return 0;
  if (t >= double(n - 1)) return n - 1;
  return static_cast<int>(t);
}

// t truncated to int64, saturated at the type's limits; NaN gives 0. For counts that are
// reported (element estimates) before a budget check refuses them.
inline std::int64_t saturatedInt64(double t) {
  if (!(t > -9.2e18)) return t < 0 ? INT64_MIN : 0;
  if (t >= 9.2e18) return INT64_MAX;
  return static_cast<std::int64_t>(t);
}

}  // namespace anisomesh

// Shortest round-trip number text for messages (see number_text.h).
#include "anisomesh/core/number_text.h"

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace anisomesh {

std::string numberText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

void appendDoubleBits(std::string& out, double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016" PRIx64 " ", u);
  out += buf;
}

}  // namespace anisomesh

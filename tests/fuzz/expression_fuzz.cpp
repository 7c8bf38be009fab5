// libFuzzer target: the expression parser and its two evaluation paths. value() (plain
// doubles) and evaluate().f (second-order duals) must agree: both NaN, both the same
// infinity, or within a relative 1e-9 (absolute 1e-300 near zero) -- the dual path does
// the same operations on the value part, so any larger gap is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/expression.h"

namespace {
bool agree(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  if (std::isinf(a) || std::isinf(b)) return a == b;
  return std::fabs(a - b) <= 1e-9 * std::fmax(std::fabs(a), std::fabs(b)) + 1e-300;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  anisomesh::ExpressionOptions o;
  o.parameters = {{"a", 0.5}};
  try {
    const anisomesh::Expression e = anisomesh::Expression::parse(text, o);
    const double points[][2] = {{0.0, 0.0}, {0.3, -0.7}, {-2.5, 1.25}, {10.0, 3.0}, {1e-8, 1e8}};
    for (const auto& p : points)
      if (!agree(e.value(p[0], p[1]), e.evaluate(p[0], p[1]).f)) __builtin_trap();
  } catch (const anisomesh::Error&) {
  }
  return 0;
}

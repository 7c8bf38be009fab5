// Writing doubles as "%.17g": formatG17 (the wasm build's writer) against snprintf and
// std::to_chars (the native writer), over mesh-like coordinates.
#include <benchmark/benchmark.h>

#include <charconv>
#include <cstdio>
#include <random>
#include <vector>

#include "anisomesh/core/number_text.h"

namespace {

std::vector<double> coordinates() {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> d(-2.0, 2.0);
  std::vector<double> v(1024);
  for (double& x : v) x = d(rng);
  return v;
}

void BM_FormatG17(benchmark::State& state) {
  const auto xs = coordinates();
  char buf[32];
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(anisomesh::formatG17(xs[i++ & 1023], buf));
}
BENCHMARK(BM_FormatG17);

void BM_SnprintfG17(benchmark::State& state) {
  const auto xs = coordinates();
  char buf[32];
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(std::snprintf(buf, sizeof buf, "%.17g", xs[i++ & 1023]));
}
BENCHMARK(BM_SnprintfG17);

#if defined(__cpp_lib_to_chars)  // (floating to_chars: libstdc++ 11, libc++ 14 and later)
void BM_ToCharsG17(benchmark::State& state) {
  const auto xs = coordinates();
  char buf[32];
  size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(std::to_chars(buf, buf + sizeof buf, xs[i++ & 1023], std::chars_format::general, 17));
}
BENCHMARK(BM_ToCharsG17);
#endif

}  // namespace

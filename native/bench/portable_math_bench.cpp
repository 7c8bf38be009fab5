// anisomesh::pm (portable, bit-reproducible math) versus the platform libm.
// Each benchmark evaluates the function over a ring of 1024 precomputed
// inputs; compare BM_Pm_<f> with BM_Std_<f>.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "anisomesh/core/portable_math.h"

namespace pm = anisomesh::pm;

namespace {

std::vector<double> inputs(double lo, double hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> d(lo, hi);
  std::vector<double> v(1024);
  for (double& x : v) x = d(rng);
  return v;
}

template <double (*F)(double)>
void run1(benchmark::State& state, double lo, double hi) {
  const auto xs = inputs(lo, hi, 1);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(F(xs[i & 1023]));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}

template <double (*F)(double, double)>
void run2(benchmark::State& state, double lo, double hi, double lo2, double hi2) {
  const auto xs = inputs(lo, hi, 1);
  const auto ys = inputs(lo2, hi2, 2);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(F(xs[i & 1023], ys[i & 1023]));
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}

#define PM_BENCH1(name, lo, hi)                                                                          \
  double std_##name(double x) { return std::name(x); }                                                   \
  void BM_Std_##name(benchmark::State& s) { run1<std_##name>(s, lo, hi); }                               \
  void BM_Pm_##name(benchmark::State& s) { run1<static_cast<double (*)(double)>(pm::name)>(s, lo, hi); } \
  BENCHMARK(BM_Std_##name);                                                                              \
  BENCHMARK(BM_Pm_##name);

#define PM_BENCH2(name, lo, hi, lo2, hi2)                                            \
  double std_##name(double x, double y) { return std::name(x, y); }                  \
  void BM_Std_##name(benchmark::State& s) { run2<std_##name>(s, lo, hi, lo2, hi2); } \
  void BM_Pm_##name(benchmark::State& s) {                                           \
    run2<static_cast<double (*)(double, double)>(pm::name)>(s, lo, hi, lo2, hi2);    \
  }                                                                                  \
  BENCHMARK(BM_Std_##name);                                                          \
  BENCHMARK(BM_Pm_##name);

PM_BENCH1(exp, -20.0, 20.0)
PM_BENCH1(log, 1e-3, 1e3)
PM_BENCH1(log2, 1e-3, 1e3)
PM_BENCH1(sin, -10.0, 10.0)
PM_BENCH1(cos, -10.0, 10.0)
PM_BENCH1(tan, -10.0, 10.0)
PM_BENCH1(atan, -10.0, 10.0)
PM_BENCH1(asin, -1.0, 1.0)
PM_BENCH1(acos, -1.0, 1.0)
PM_BENCH1(sinh, -5.0, 5.0)
PM_BENCH1(cosh, -5.0, 5.0)
PM_BENCH1(tanh, -5.0, 5.0)
PM_BENCH2(atan2, -10.0, 10.0, -10.0, 10.0)
PM_BENCH2(hypot, -10.0, 10.0, -10.0, 10.0)
PM_BENCH2(pow, 0.01, 10.0, -5.0, 5.0)

// pow with small integer exponents (common in metric code: h^-2, x^3).
double stdPowInt(double x, double y) { return std::pow(x, std::floor(y)); }
double pmPowInt(double x, double y) { return pm::pow(x, std::floor(y)); }
void BM_Std_powInt(benchmark::State& s) { run2<stdPowInt>(s, 0.01, 10.0, -8.0, 9.0); }
void BM_Pm_powInt(benchmark::State& s) { run2<pmPowInt>(s, 0.01, 10.0, -8.0, 9.0); }
BENCHMARK(BM_Std_powInt);
BENCHMARK(BM_Pm_powInt);

}  // namespace

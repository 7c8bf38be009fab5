// formatG17 (the wasm build's writer of mesh coordinates and metrics) gives the bytes of
// printf's "%.17g" for every double: its exact integer path in [1e-5, ~1e17) and the
// C library beyond. appendDoubleBits (cache keys) gives those of "%016" PRIx64 " ".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "anisomesh/core/number_text.h"

namespace anisomesh {
namespace {

std::string viaPrintf(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string viaFormat(double v) {
  char buf[40];
  const int n = formatG17(v, buf);
  EXPECT_EQ(n, static_cast<int>(std::strlen(buf)));
  return std::string(buf, static_cast<size_t>(n));
}

double fromBits(std::uint64_t b) {
  double v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

TEST(FormatG17, MatchesPrintfOnChosenValues) {
  const double values[] = {0.0,
                           -0.0,
                           1.0,
                           -1.0,
                           0.1,
                           0.5,
                           2.0 / 3.0,
                           1e-5,
                           9.9999999999999991e-6,
                           1e-4,
                           0.001,
                           1e15,
                           1e16,
                           1e17,
                           123456789.125,
                           99999999999999999.0,
                           0.30000000000000004,
                           9.9999999999999995e-5,
                           0.99999999999999989,
                           9.9999999999999982,
                           1e-300,
                           5e-324,
                           1.7976931348623157e308,
                           INFINITY,
                           -INFINITY,
                           NAN,
                           4503599627370495.5,
                           9007199254740993.0,
                           1e14 + 0.125,
                           1e14 + 0.375,
                           1e13 + 0.0625,
                           1e12 + 0.03125 * 3};
  for (double v : values) EXPECT_EQ(viaFormat(v), viaPrintf(v)) << "value bits of " << viaPrintf(v);
}

// Exact ties at the 17th digit (x * 10^p ends in .5): rounded to even as printf does.
TEST(FormatG17, RoundsTiesToEvenAsPrintf) {
  int ties = 0;
  for (int e = 10; e <= 15; ++e)
    for (int j = 1; j < 400; ++j) {
      const double v = std::pow(10.0, e) + j / 64.0;
      const std::string p = viaPrintf(v);
      EXPECT_EQ(viaFormat(v), p);
      long long tenth = 1;  // v * 10^(16 - e) = integer + j * 10^(16 - e) / 64: a tie at remainder 32
      for (int k = 0; k < 16 - e; ++k) tenth *= 10;
      ties += (j * tenth) % 64 == 32;
    }
  EXPECT_GT(ties, 0);
}

TEST(FormatG17, MatchesPrintfOnRandomDoubles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0), exponent(-12.0, 22.0);
  for (int i = 0; i < 300000; ++i) {
    const double a = coordinate(rng), b = std::pow(10.0, exponent(rng)) * (i % 2 ? -1 : 1);
    const double c = fromBits(rng());  // any bits: every range and kind
    ASSERT_EQ(viaFormat(a), viaPrintf(a));
    ASSERT_EQ(viaFormat(b), viaPrintf(b));
    ASSERT_EQ(viaFormat(c), viaPrintf(c));
  }
  // Neighbours of powers of ten and of numbers with few digits (the exponent estimate).
  for (int k = -8; k <= 20; ++k) {
    const double p = std::pow(10.0, k);
    double x = p;
    for (int s = 0; s < 40; ++s) x = std::nextafter(x, 0.0);
    for (int s = 0; s < 80; ++s, x = std::nextafter(x, INFINITY)) ASSERT_EQ(viaFormat(x), viaPrintf(x));
    for (int d = 1; d < 1000; d += 7) ASSERT_EQ(viaFormat(d * p / 1000), viaPrintf(d * p / 1000));
  }
}

// appendDoubleBits writes a double's bits as "%016" PRIx64 " " does: checked on special
// values and random bit patterns (NaNs with payloads, subnormals, negative zero included).
TEST(DoubleBits, MatchesPrintfHex) {
  std::mt19937_64 rng(7);
  std::vector<std::uint64_t> bits = {0, 0x8000000000000000ull, 0x7ff0000000000000ull, 0xfff8000000000001ull,
                                     1, 0x000fffffffffffffull, 0x3ff0000000000000ull, ~0ull};
  for (int k = 0; k < 20000; ++k) bits.push_back(rng());
  std::string got, expected;
  for (std::uint64_t u : bits) {
    double x;
    std::memcpy(&x, &u, sizeof x);
    appendDoubleBits(got, x);
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx ", static_cast<unsigned long long>(u));
    expected += buf;
  }
  EXPECT_EQ(got, expected);
}

}  // namespace
}  // namespace anisomesh

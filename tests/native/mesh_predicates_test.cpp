#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "anisomesh/mesh/predicates.h"

using namespace anisomesh;

namespace {
int sgn(double x) { return (x > 0) - (x < 0); }
}  // namespace

// a near (0.5, 0.5) perturbed by ulps, b and c on y = x: the exact sign is sign(ay - ax).
TEST(MeshPredicates, Orient2dExactOnNearlyCollinearPoints) {
  const double u = std::ldexp(1.0, -53);
  const Vec2 b(12.0, 12.0), c(24.0, 24.0);
  int naiveWrong = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Vec2 a(0.5 + i * u, 0.5 + j * u);
      const int expected = sgn(static_cast<double>(j - i));
      EXPECT_EQ(sgn(orient2d(a, b, c)), expected) << i << " " << j;
      EXPECT_EQ(sgn(orient2d(b, c, a)), expected);
      EXPECT_EQ(sgn(orient2d(c, a, b)), expected);
      EXPECT_EQ(sgn(orient2d(b, a, c)), -expected);
      if (sgn(orient2dNaive(a, b, c)) != expected) ++naiveWrong;
    }
  EXPECT_GT(naiveWrong, 0) << "the configuration should defeat plain doubles";
}

TEST(MeshPredicates, Orient2dBasic) {
  EXPECT_GT(orient2d(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)), 0.0);
  EXPECT_LT(orient2d(Vec2(0, 0), Vec2(0, 1), Vec2(1, 0)), 0.0);
  EXPECT_EQ(orient2d(Vec2(0, 0), Vec2(1, 1), Vec2(3, 3)), 0.0);
  EXPECT_EQ(orient2d(Vec2(0.1, 0.1), Vec2(0.2, 0.2), Vec2(0.3, 0.3)) == 0.0,
            orient2d(Vec2(0.3, 0.3), Vec2(0.1, 0.1), Vec2(0.2, 0.2)) == 0.0);
}

// The corners of any axis-aligned rectangle are exactly cocircular; nudging the fourth
// corner by one ulp away from / towards the centre puts it outside / inside.
TEST(MeshPredicates, IncircleExactOnCocircularRectangles) {
  int naiveNonZero = 0;
  unsigned s = 7;
  auto rnd = [&s]() {
    s = s * 1103515245u + 12345u;
    return static_cast<double>((s >> 8) & 0xffffff) / 16777216.0;
  };
  for (int k = 0; k < 2000; ++k) {
    const double x0 = 100.0 * rnd() + 0.1 * rnd(), y0 = -50.0 * rnd() + 1e-3 * rnd();
    const double x1 = x0 + 1e-3 + rnd(), y1 = y0 + 1e-3 + 3.0 * rnd();
    const Vec2 a(x0, y0), b(x1, y0), c(x1, y1), d(x0, y1);
    EXPECT_EQ(incircle(a, b, c, d), 0.0);
    EXPECT_EQ(incircle(b, c, d, a), 0.0);
    EXPECT_EQ(incircle(d, b, c, a), 0.0);
    if (incircleNaive(a, b, c, d) != 0.0 || incircleNaive(b, c, d, a) != 0.0 || incircleNaive(c, d, a, b) != 0.0)
      ++naiveNonZero;
    const Vec2 out(std::nextafter(x0, -1e300), y1), in(std::nextafter(x0, 1e300), y1);
    EXPECT_LT(incircle(a, b, c, out), 0.0);
    EXPECT_GT(incircle(a, b, c, in), 0.0);
    EXPECT_GT(incircle(a, c, b, out), 0.0);  // clockwise reverses the sign
  }
  EXPECT_GT(naiveNonZero, 0) << "the configuration should defeat plain doubles";
}

TEST(MeshPredicates, IncircleBasic) {
  const Vec2 a(0, 0), b(1, 0), c(0, 1);
  EXPECT_GT(incircle(a, b, c, Vec2(0.5, 0.5)), 0.0);
  EXPECT_LT(incircle(a, b, c, Vec2(2, 2)), 0.0);
  EXPECT_EQ(incircle(a, b, c, Vec2(1, 1)), 0.0);
}

// Lattice points on the circle x^2 + y^2 = 32045^2 (it has many), the fourth nudged by one
// unit or not, shifted far from the origin and scaled by a power of two (all exact in
// doubles): the exact stage's sign matches the determinant computed in 128-bit integers.
TEST(MeshPredicates, IncircleExactStageMatchesIntegerArithmetic) {
  const long long r = 5LL * 13 * 17 * 29;
  std::vector<std::array<long long, 2>> onCircle;
  for (long long x = -r; x <= r; ++x) {
    const long long y2 = r * r - x * x;
    const long long y = std::llround(std::sqrt(static_cast<double>(y2)));
    if (y * y == y2) {
      onCircle.push_back({x, y});
      if (y != 0) onCircle.push_back({x, -y});
    }
  }
  ASSERT_GT(onCircle.size(), 40u);
  unsigned s = 11;
  auto pick = [&]() {
    s = s * 1103515245u + 12345u;
    return (s >> 8) % onCircle.size();
  };
  int exactZero = 0, positive = 0, negative = 0;
  for (int k = 0; k < 3000; ++k) {
    std::array<long long, 2> p[4] = {onCircle[pick()], onCircle[pick()], onCircle[pick()], onCircle[pick()]};
    p[3][k % 2] += (k / 2) % 3 - 1;  // nudged by -1, 0 or +1
    const long long shift = 1LL << (20 + k % 7);
    const double scale = std::ldexp(1.0, -(k % 40));
    double q[4][2];
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 2; ++j) q[i][j] = static_cast<double>(p[i][j] + shift) * scale;
    __int128 d[3][2], lift[3];
    for (int i = 0; i < 3; ++i) {
      d[i][0] = p[i][0] - p[3][0];
      d[i][1] = p[i][1] - p[3][1];
      lift[i] = d[i][0] * d[i][0] + d[i][1] * d[i][1];
    }
    const __int128 det = lift[0] * (d[1][0] * d[2][1] - d[2][0] * d[1][1]) +
                         lift[1] * (d[2][0] * d[0][1] - d[0][0] * d[2][1]) +
                         lift[2] * (d[0][0] * d[1][1] - d[1][0] * d[0][1]);
    const int expected = (det > 0) - (det < 0);
    ASSERT_EQ(sgn(incircle(q[0], q[1], q[2], q[3])), expected) << k;
    exactZero += expected == 0;
    positive += expected > 0;
    negative += expected < 0;
  }
  EXPECT_GT(exactZero, 100);
  EXPECT_GT(positive, 100);
  EXPECT_GT(negative, 100);
}

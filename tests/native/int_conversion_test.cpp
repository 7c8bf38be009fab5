// core/int_conversion.h: double-to-integer conversions that stay defined for any double
// (the grid cells of bucket grids and point locators, reported element estimates).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "anisomesh/core/int_conversion.h"

using namespace anisomesh;

TEST(IntConversion, ClampedCellIsTheFloorClampedToTheGrid) {
  for (double t : {-3.5, -0.0, 0.0, 0.99, 1.0, 2.5, 6.999, 7.0, 8.0})
    EXPECT_EQ(clampedCell(t, 8), std::clamp(static_cast<int>(std::floor(t)), 0, 7)) << t;
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(clampedCell(2e27, 8), 7);  // the fuzz finding's cell (bucket_grid.h)
  EXPECT_EQ(clampedCell(-2e27, 8), 0);
  EXPECT_EQ(clampedCell(inf, 8), 7);
  EXPECT_EQ(clampedCell(-inf, 8), 0);
  EXPECT_EQ(clampedCell(std::nan(""), 8), 0);
  EXPECT_EQ(clampedCell(5.0, 1), 0);
}

TEST(IntConversion, SaturatedInt64KeepsExactValuesAndSaturates) {
  EXPECT_EQ(saturatedInt64(0.0), 0);
  EXPECT_EQ(saturatedInt64(1234567.9), 1234567);
  EXPECT_EQ(saturatedInt64(-1234567.9), -1234567);
  EXPECT_EQ(saturatedInt64(9.0e18), std::int64_t(9000000000000000000));
  EXPECT_EQ(saturatedInt64(1e30), INT64_MAX);
  EXPECT_EQ(saturatedInt64(-1e30), INT64_MIN);
  EXPECT_EQ(saturatedInt64(std::numeric_limits<double>::infinity()), INT64_MAX);
  EXPECT_EQ(saturatedInt64(std::nan("")), 0);
}

// Bresenham traversal: shapes of axis-aligned, diagonal and steep rays, zero length, and clipping.
#include "mapper/core/ray_trace.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace slam::mapper {
namespace {

using Cells = std::vector<std::pair<int, int>>;

Cells trace(int x0, int y0, int x1, int y1, int w, int h, bool include_end, int64_t* count = nullptr) {
  Cells out;
  const int64_t n = trace_ray(x0, y0, x1, y1, w, h, include_end, [&](size_t i) {
    out.emplace_back(static_cast<int>(i % static_cast<size_t>(w)),
                     static_cast<int>(i / static_cast<size_t>(w)));
  });
  if (count) *count = n;
  return out;
}

TEST(RayTrace, AxisAlignedInEveryDirection) {
  EXPECT_EQ(trace(2, 2, 5, 2, 10, 10, true), (Cells{{2, 2}, {3, 2}, {4, 2}, {5, 2}}));
  EXPECT_EQ(trace(5, 2, 2, 2, 10, 10, true), (Cells{{5, 2}, {4, 2}, {3, 2}, {2, 2}}));
  EXPECT_EQ(trace(3, 1, 3, 4, 10, 10, true), (Cells{{3, 1}, {3, 2}, {3, 3}, {3, 4}}));
  EXPECT_EQ(trace(3, 4, 3, 1, 10, 10, true), (Cells{{3, 4}, {3, 3}, {3, 2}, {3, 1}}));
}

TEST(RayTrace, EndCellOnlyWhenAsked) {
  EXPECT_EQ(trace(2, 2, 5, 2, 10, 10, false), (Cells{{2, 2}, {3, 2}, {4, 2}}));
}

TEST(RayTrace, DiagonalStepsBothAxesAtOnce) {
  EXPECT_EQ(trace(0, 0, 3, 3, 10, 10, true), (Cells{{0, 0}, {1, 1}, {2, 2}, {3, 3}}));
  EXPECT_EQ(trace(3, 0, 0, 3, 10, 10, true), (Cells{{3, 0}, {2, 1}, {1, 2}, {0, 3}}));
}

TEST(RayTrace, SteepRayVisitsOneCellPerRow) {
  int64_t n = 0;
  const Cells c = trace(1, 0, 3, 8, 10, 10, true, &n);
  ASSERT_EQ(c.size(), 9u);
  EXPECT_EQ(n, 9);
  for (size_t i = 0; i < c.size(); ++i) EXPECT_EQ(c[i].second, static_cast<int>(i));
  EXPECT_EQ(c.front(), (std::pair{1, 0}));
  EXPECT_EQ(c.back(), (std::pair{3, 8}));
  for (size_t i = 1; i < c.size(); ++i) EXPECT_LE(std::abs(c[i].first - c[i - 1].first), 1);
}

TEST(RayTrace, ZeroLength) {
  EXPECT_EQ(trace(4, 4, 4, 4, 10, 10, true), (Cells{{4, 4}}));
  EXPECT_TRUE(trace(4, 4, 4, 4, 10, 10, false).empty());
}

TEST(RayTrace, LeavingTheGridIsClipped) {
  int64_t n = 0;
  EXPECT_EQ(trace(7, 1, 14, 1, 10, 5, true, &n), (Cells{{7, 1}, {8, 1}, {9, 1}}));
  EXPECT_EQ(n, 3);
  // Entering from outside: visited from the first inside cell.
  EXPECT_EQ(trace(-3, 2, 1, 2, 10, 5, true), (Cells{{0, 2}, {1, 2}}));
  // Never inside.
  EXPECT_TRUE(trace(-5, -5, -1, 20, 10, 5, true).empty());
  // Crossing the whole grid from outside to outside.
  EXPECT_EQ(trace(-2, 0, 12, 0, 4, 1, true).size(), 4u);
}

}  // namespace
}  // namespace slam::mapper

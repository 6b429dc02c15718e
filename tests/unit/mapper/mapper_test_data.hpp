#pragma once
// What the mapper's unit tests share: a small grid layout and one robot's observation of a wall.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper::test_data {

// 0.1 m cells, 4 m x 4 m around the origin, growable to 20 m.
inline GridConfig small() {
  GridConfig c;
  c.resolution = 0.1;
  c.origin_x = -2.0;
  c.origin_y = -2.0;
  c.width_m = 4.0;
  c.height_m = 4.0;
  c.max_extent_m = 20.0;
  return c;
}

// Same layout; every cell's log-odds, class octet and inflation count.
inline void expect_same(const OccupancyGrid& a, const OccupancyGrid& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  ASSERT_EQ(a.origin_x(), b.origin_x());
  ASSERT_EQ(a.origin_y(), b.origin_y());
  int64_t differ = 0;
  for (int32_t y = 0; y < a.height(); ++y)
    for (int32_t x = 0; x < a.width(); ++x)
      if (a.log_odds(x, y) != b.log_odds(x, y) || a.cell_class(x, y) != b.cell_class(x, y) ||
          a.inflation_count(x, y) != b.inflation_count(x, y))
        ++differ;
  EXPECT_EQ(differ, 0) << "cells differ";
}

// A robot at the origin seeing a wall at x = 1.03, integrated into `grid` and stored in `store`.
inline void feed(OccupancyGrid& grid, ObservationStore& store) {
  std::vector<Vec2> hits;
  for (int i = -5; i <= 5; ++i) hits.push_back({1.03, 0.1 * i + 0.03});
  ObservationView v;
  v.hits = hits;
  ASSERT_TRUE(grid.integrate(v));
  ASSERT_TRUE(store.append("r1", 1, 0, 0, v));
  ASSERT_TRUE(store.flush());
}

// Same layout, log-odds and classes in every cell.
inline bool same_grid(const OccupancyGrid& a, const OccupancyGrid& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.origin_x() != b.origin_x() ||
      a.origin_y() != b.origin_y())
    return false;
  for (int32_t y = 0; y < a.height(); ++y)
    for (int32_t x = 0; x < a.width(); ++x)
      if (a.log_odds(x, y) != b.log_odds(x, y) || a.cell_class(x, y) != b.cell_class(x, y)) return false;
  return true;
}

}  // namespace slam::mapper::test_data

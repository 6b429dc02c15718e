#pragma once
// Test helper: builds PlanningGrids from ASCII art ('.' free, '#' occupied, 'i' inflated,
// 'x' obstructed, '?' unknown), first text row = highest y, so pictures read like maps.
#include <string>
#include <vector>

#include "planner/core/planning_grid.hpp"

namespace slam::planner::test {

inline PlanningGrid grid_from_art(const std::vector<std::string>& rows, double resolution = 1.0,
                                  Vec2 origin = {0.0, 0.0}) {
  const auto h = static_cast<int32_t>(rows.size());
  const auto w = static_cast<int32_t>(rows.front().size());
  std::vector<uint8_t> cells(static_cast<size_t>(w) * static_cast<size_t>(h), kCellFree);
  for (int32_t r = 0; r < h; ++r) {
    const int32_t y = h - 1 - r;
    for (int32_t x = 0; x < w; ++x) {
      uint8_t v = kCellFree;
      switch (rows[r][x]) {
        case '#':
          v = kCellOccupied;
          break;
        case 'i':
          v = kCellFree | kCellInflated;
          break;
        case 'x':
          v = kCellFree | kCellObstructed;
          break;
        case '?':
          v = kCellUnknown;
          break;
        default:
          break;
      }
      cells[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)] = v;
    }
  }
  PlanningGrid grid;
  if (!grid.reset(GridGeometry{origin, resolution, w, h}, 1, 0, std::move(cells))) return {};
  return grid;
}

inline PlanningGrid uniform_grid(int32_t w, int32_t h, uint8_t value, double resolution = 1.0) {
  const GridGeometry geometry{{0.0, 0.0}, resolution, w, h};
  PlanningGrid grid;
  if (!grid.reset(geometry, 1, 0, std::vector<uint8_t>(geometry.cells(), value))) {
    return {};
  }
  return grid;
}

}  // namespace slam::planner::test

#pragma once
// Test helper: builds PlanningGrids from ASCII art ('.' free, '#' occupied, 'i' inflated,
// 'x' obstructed, '?' unknown), first text row = highest y, so pictures read like maps.
#include <string>
#include <vector>

#include "planner/planning_grid.hpp"

namespace slam::planner::test {

inline PlanningGrid grid_from_art(const std::vector<std::string>& rows, double resolution = 1.0,
                                  Vec2 origin = {0.0, 0.0}) {
  const auto h = static_cast<uint32_t>(rows.size());
  const auto w = static_cast<uint32_t>(rows.front().size());
  std::vector<uint8_t> cells(static_cast<size_t>(w) * h, kCellFree);
  for (uint32_t r = 0; r < h; ++r) {
    const uint32_t y = h - 1 - r;
    for (uint32_t x = 0; x < w; ++x) {
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
      cells[static_cast<size_t>(y) * w + x] = v;
    }
  }
  PlanningGrid grid;
  if (!grid.reset(GridGeometry{w, h, resolution, origin}, 1, 0, std::move(cells))) return {};
  return grid;
}

inline PlanningGrid uniform_grid(uint32_t w, uint32_t h, uint8_t value, double resolution = 1.0) {
  PlanningGrid grid;
  if (!grid.reset(GridGeometry{w, h, resolution, {0.0, 0.0}}, 1, 0,
                  std::vector<uint8_t>(static_cast<size_t>(w) * h, value))) {
    return {};
  }
  return grid;
}

}  // namespace slam::planner::test

#pragma once
// Ground truth for judging a mapped grid: the simulator's hidden world rasterised on cells aligned
// with the grid's. A cell is free space when its centre lies in the world, outside furniture and
// at least half a cell from every wall (so cells a wall runs through are neither required nor
// counted); it is reachable when a 4-connected walk from a robot's start gets there without a
// step crossing a wall. The score says how much of the reachable free space the grid shows as
// free (coverage) and how many of the cells it claims to know agree with the world (agreement).
#include <cmath>
#include <cstdint>
#include <vector>

#include "simulator/core/world.hpp"

namespace slam::testkit {

// The layout of a grid (GridInfo in map.idl), row 0 the lowest y.
struct TruthLayout {
  uint32_t width = 0;
  uint32_t height = 0;
  double resolution = 0.05;
  double origin_x = 0.0;
  double origin_y = 0.0;
};

struct MapScore {
  size_t reachable = 0;  // reachable free cells of the world
  size_t covered = 0;    // of those, free in the grid
  size_t observed = 0;   // grid cells inside the world bounds that are free or occupied
  size_t agreeing = 0;   // of those, the ones the world bears out
  double coverage() const {
    return reachable == 0 ? 0.0 : static_cast<double>(covered) / static_cast<double>(reachable);
  }
  double agreement() const {
    return observed == 0 ? 0.0 : static_cast<double>(agreeing) / static_cast<double>(observed);
  }
};

class WorldTruth {
 public:
  // Rasterises `world` on cells aligned with `grid` (same resolution, cell edges on the same
  // lines) but covering the whole world, whatever part of it the grid spans so far, and floods the
  // free space from `starts` (map frame).
  WorldTruth(const sim::World& world, const TruthLayout& grid, const std::vector<Vec2>& starts)
      : world_(world) {
    const sim::Bounds& b = world.bounds();
    const double res = grid.resolution;
    offset_x_ = static_cast<int64_t>(std::floor((b.min.x - grid.origin_x) / res)) - 1;
    offset_y_ = static_cast<int64_t>(std::floor((b.min.y - grid.origin_y) / res)) - 1;
    layout_.resolution = res;
    layout_.origin_x = grid.origin_x + static_cast<double>(offset_x_) * res;
    layout_.origin_y = grid.origin_y + static_cast<double>(offset_y_) * res;
    layout_.width = static_cast<uint32_t>(std::ceil((b.max.x - layout_.origin_x) / res)) + 1;
    layout_.height = static_cast<uint32_t>(std::ceil((b.max.y - layout_.origin_y) / res)) + 1;
    rasterise();
    flood(starts);
  }

  size_t reachable_count() const { return reachable_count_; }

  // Scores a grid's class octets (CELL_* in map.idl, state in the low two bits) laid out as
  // `grid`, aligned like the grid the truth was made for; world cells the grid does not span yet
  // count as unknown. An occupied cell agrees when a wall (or furniture, or the world's edge) lies
  // within `wall_tolerance_m` of its centre; a free cell agrees when no wall comes within a quarter
  // cell of its centre (a wall clipping a corner of a free cell is not an error).
  MapScore score(const TruthLayout& grid, const std::vector<uint8_t>& cells, double wall_tolerance_m) const {
    MapScore s;
    s.reachable = reachable_count_;
    const sim::Bounds& b = world_.bounds();
    for (uint32_t y = 0; y < layout_.height; ++y) {
      for (uint32_t x = 0; x < layout_.width; ++x) {
        const int64_t gx = int64_t{x} + offset_x_;
        const int64_t gy = int64_t{y} + offset_y_;
        if (gx < 0 || gy < 0 || gx >= grid.width || gy >= grid.height) continue;
        const size_t g = static_cast<size_t>(gy) * grid.width + static_cast<size_t>(gx);
        const auto state = static_cast<uint8_t>(cells[g] & 3u);
        if (reachable_[index(x, y)] != 0 && state == kFree) ++s.covered;
        const Vec2 c = centre(x, y);
        if (!b.contains(c) || (state != kFree && state != kOccupied)) continue;
        ++s.observed;
        const bool ok = state == kFree ? world_.is_free(c, 0.25 * layout_.resolution)
                                       : !world_.is_free(c, wall_tolerance_m);
        if (ok) ++s.agreeing;
      }
    }
    return s;
  }

 private:
  static constexpr uint8_t kFree = 1;      // CELL_FREE
  static constexpr uint8_t kOccupied = 2;  // CELL_OCCUPIED

  void rasterise() {
    const size_t n = static_cast<size_t>(layout_.width) * layout_.height;
    free_.assign(n, 0);
    reachable_.assign(n, 0);
    for (uint32_t y = 0; y < layout_.height; ++y) {
      for (uint32_t x = 0; x < layout_.width; ++x) {
        free_[index(x, y)] = world_.is_free(centre(x, y), 0.5 * layout_.resolution) ? 1 : 0;
      }
    }
  }

  void flood(const std::vector<Vec2>& starts) {
    std::vector<size_t> queue;
    for (const Vec2& s : starts) {
      const double cx = std::floor((s.x - layout_.origin_x) / layout_.resolution);
      const double cy = std::floor((s.y - layout_.origin_y) / layout_.resolution);
      if (cx < 0 || cy < 0 || cx >= layout_.width || cy >= layout_.height) continue;
      const size_t i = index(static_cast<uint32_t>(cx), static_cast<uint32_t>(cy));
      if (free_[i] == 0 || reachable_[i] != 0) continue;
      reachable_[i] = 1;
      queue.push_back(i);
    }
    const int steps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (size_t head = 0; head < queue.size(); ++head) {
      const auto x = static_cast<uint32_t>(queue[head] % layout_.width);
      const auto y = static_cast<uint32_t>(queue[head] / layout_.width);
      for (const auto& d : steps) {
        const int64_t nx = int64_t{x} + d[0];
        const int64_t ny = int64_t{y} + d[1];
        if (nx < 0 || ny < 0 || nx >= layout_.width || ny >= layout_.height) continue;
        const size_t j = index(static_cast<uint32_t>(nx), static_cast<uint32_t>(ny));
        if (free_[j] == 0 || reachable_[j] != 0) continue;
        // Both centres may be clear of walls with a wall between them: the step must not cross it.
        const Vec2 dir{static_cast<double>(d[0]), static_cast<double>(d[1])};
        if (world_.cast(centre(x, y), dir, layout_.resolution) < layout_.resolution) continue;
        reachable_[j] = 1;
        queue.push_back(j);
      }
    }
    reachable_count_ = queue.size();
  }

  size_t index(uint32_t x, uint32_t y) const { return static_cast<size_t>(y) * layout_.width + x; }
  Vec2 centre(uint32_t x, uint32_t y) const {
    return {layout_.origin_x + (x + 0.5) * layout_.resolution,
            layout_.origin_y + (y + 0.5) * layout_.resolution};
  }

  const sim::World& world_;
  TruthLayout layout_;  // covers the world; its cell (x, y) is the grid's (x + offset_x_, y + offset_y_)
  int64_t offset_x_ = 0;
  int64_t offset_y_ = 0;
  std::vector<uint8_t> free_;
  std::vector<uint8_t> reachable_;
  size_t reachable_count_ = 0;
};

}  // namespace slam::testkit

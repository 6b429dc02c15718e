#pragma once
// The compacted part of the store: the log-odds a full rebuild had after replaying every observation up
// to a row (`through_row`), kept per tile of 32 x 32 cells (only tiles with a known cell), in the layout
// the grid had then. A rebuild starts from it instead of unknown cells (and the prior it already holds):
// the rows it replaces are gone, and a fold that starts from the state after row R and replays the
// rows after R ends where the whole fold ends, cell for cell (compaction.hpp).
// Plain C++, no SQLite.
#include <cstdint>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/grid_tiles.hpp"
#include "mapper/core/footprint_index.hpp"

namespace slam::mapper {

class OccupancyGrid;

struct BaselineTile {
  static constexpr int32_t kSide = kGridTileSide;
  int32_t tx = 0;  // tile column and row in the baseline's layout
  int32_t ty = 0;
  std::vector<int16_t> cells;  // kSide * kSide log-odds, row-major; cells past the layout's edge are 0
};

struct Baseline {
  GridGeometry geometry;            // the layout the log-odds were drawn in
  int64_t through_row = 0;          // every observation up to this row is in it (and gone from the store)
  bool prior_pending = false;       // a prior was imported after it: a rebuild applies that prior over it
  std::vector<BaselineTile> tiles;  // ascending (ty, tx); a region load holds only the tiles it asked for

  bool empty() const { return tiles.empty(); }
  // Calls f(map-frame centre of the cell, log-odds) for every known cell.
  template <class F>
  void for_each_known(F&& f) const {
    const double res = geometry.resolution;
    for (const BaselineTile& t : tiles)
      for (int32_t i = 0; i < BaselineTile::kSide * BaselineTile::kSide; ++i) {
        const int16_t v = t.cells[static_cast<size_t>(i)];
        if (v == 0) continue;
        const int32_t x = t.tx * BaselineTile::kSide + i % BaselineTile::kSide;
        const int32_t y = t.ty * BaselineTile::kSide + i / BaselineTile::kSide;
        f(Vec2{geometry.origin.x + (x + 0.5) * res, geometry.origin.y + (y + 0.5) * res}, v);
      }
  }
  // The map-frame box of the whole layout.
  MapBox box() const;
};

// The grid's log-odds as a baseline through `through_row` (obstructions are not log-odds: not in it).
Baseline baseline_of(const OccupancyGrid& grid, int64_t through_row);

}  // namespace slam::mapper

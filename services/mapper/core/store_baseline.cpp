// Baseline: a grid's log-odds kept per known tile (see store_baseline.hpp).
#include "mapper/core/store_baseline.hpp"

#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper {

MapBox Baseline::box() const {
  MapBox b;
  b.add(geometry.origin);
  b.add(Vec2{geometry.origin.x + geometry.width * geometry.resolution,
             geometry.origin.y + geometry.height * geometry.resolution});
  return b;
}

Baseline baseline_of(const OccupancyGrid& grid, int64_t through_row) {
  constexpr int32_t kSide = BaselineTile::kSide;
  Baseline out;
  out.geometry = grid.geometry();
  out.through_row = through_row;
  const TileLayout layout{grid.width(), grid.height(), kSide};
  BaselineTile tile;
  for (int32_t ty = 0; ty < layout.tiles_y(); ++ty)
    for (int32_t tx = 0; tx < layout.tiles_x(); ++tx) {
      tile.cells.assign(static_cast<size_t>(kSide * kSide), 0);
      bool known = false;
      for (int32_t y = ty * kSide; y < std::min((ty + 1) * kSide, grid.height()); ++y)
        for (int32_t x = tx * kSide; x < std::min((tx + 1) * kSide, grid.width()); ++x) {
          const int16_t v = grid.log_odds(x, y);
          tile.cells[static_cast<size_t>((y - ty * kSide) * kSide + (x - tx * kSide))] = v;
          known = known || v != 0;
        }
      if (!known) continue;
      tile.tx = tx;
      tile.ty = ty;
      out.tiles.push_back(tile);
    }
  return out;
}

}  // namespace slam::mapper

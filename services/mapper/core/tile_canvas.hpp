#pragma once
// Some tiles of the grid drawn afresh: what a partial re-render computes on its worker while the loop
// keeps the live grid. It holds the log-odds of the chosen tiles only (4 kB per 32 x 32 tile) in the
// live grid's layout, starts them unknown (or at the stored prior) and draws observations into them
// by the grid's own rules (OccupancyGrid::integrate: hits first, one update per cell per observation,
// clamped int16 log-odds; legacy mode marks hits only); cells outside the tiles are never written.
// Replaying every observation that touches the tiles, in insertion order, gives those tiles exactly
// the log-odds a full rebuild gives them. OccupancyGrid::redraw() then copies them into the grid.
// Plain C++, no allocation per observation once reset.
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/grid_tiles.hpp"
#include "common/core/map_io.hpp"
#include "mapper/core/footprint_index.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/occupancy_grid.hpp"
#include "mapper/core/store_baseline.hpp"

namespace slam::mapper {

class TileCanvas {
 public:
  enum class Drawn {
    Yes,          // drawn (it may have touched no tile)
    Rejected,     // what the grid refuses too (not finite, beyond max_range_m): nothing drawn
    OutsideGrid,  // a point lies outside the layout: the grid would grow, so only a full rebuild is exact
  };

  // Starts over on `tiles` (ascending tile numbers of the geometry's TileLayout) with every cell unknown.
  // Allocates only when the layout or the tile count grows.
  void reset(const GridGeometry& geometry, const GridConfig& config, std::span<const uint32_t> tiles);
  // Sets the cells a stored prior covers, as OccupancyGrid::apply_prior does (call before drawing).
  void apply_prior(const MapImage& image);
  // Sets the cells a compacted baseline knows, as OccupancyGrid::apply_baseline does (call first).
  void apply_baseline(const Baseline& baseline);
  // The map-frame box of the tiles.
  MapBox box() const;
  // Whether a map-frame box overlaps any of the tiles.
  bool touches(const MapBox& box) const;
  // Draws one observation (map frame) into the tiles.
  Drawn integrate(const ObservationView& obs);

  const GridGeometry& geometry() const { return geometry_; }
  const TileLayout& layout() const { return layout_; }
  std::span<const uint32_t> tiles() const { return tiles_; }
  // Calls f(x, y, log_odds) for every grid cell of the tiles, tile by tile.
  template <class F>
  void for_each_cell(F&& f) const {
    for (size_t slot = 0; slot < tiles_.size(); ++slot) {
      const CellBox b = layout_.box(tiles_[slot]);
      for (int32_t y = b.y0; y < b.y0 + b.height; ++y)
        for (int32_t x = b.x0; x < b.x0 + b.width; ++x) f(x, y, cells_[cell_index(slot, x, y)].log_odds);
    }
  }
  size_t memory_bytes() const;

 private:
  static constexpr int32_t kSide = kGridTileSide;
  struct CanvasCell {
    int16_t log_odds = 0;
    uint16_t mark = 0;  // the observation that last updated it (one update per observation)
  };
  static_assert((kSide & (kSide - 1)) == 0, "tile sides are a power of two: cells are found by shifts");
  static constexpr int kShift = __builtin_ctz(kSide);
  static size_t cell_index(size_t slot, int32_t x, int32_t y) {  // x, y >= 0
    return slot * static_cast<size_t>(kSide * kSide) +
           static_cast<size_t>(((y & (kSide - 1)) << kShift) | (x & (kSide - 1)));
  }
  // The canvas cell of grid cell (x, y), or nullptr outside the tiles (x, y inside the grid).
  CanvasCell* at(int32_t x, int32_t y) {
    const int32_t slot = slot_of_tile_[static_cast<size_t>((y >> kShift) * tiles_x_ + (x >> kShift))];
    return slot < 0 ? nullptr : &cells_[cell_index(static_cast<size_t>(slot), x, y)];
  }
  void draw_rays(const ObservationView& obs);

  GridGeometry geometry_;
  TileLayout layout_;
  int32_t tiles_x_ = 0;
  LogOddsConfig log_odds_;
  double max_range_m_ = 0.0;
  bool legacy_ = false;
  std::vector<uint32_t> tiles_;
  std::vector<int32_t> slot_of_tile_;  // per tile of the layout: its slot, -1 when not drawn
  std::vector<CanvasCell> cells_;      // kSide x kSide per slot
  CellBox bounds_;                     // the cells the tiles span (for a quick refusal)
  uint16_t epoch_ = 0;
};

}  // namespace slam::mapper

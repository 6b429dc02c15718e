#pragma once
// The mapper's occupancy grid: clamped int16 log-odds in a flat array, the class octet of every cell
// as map.idl defines it (kept current so snapshots and patches are plain copies), an incremental
// inflation layer, manual obstructions, growth and dirty-tile tracking. Plain C++, not thread-safe:
// the service serialises calls.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/core/cell_class.hpp"
#include "common/core/geometry.hpp"
#include "common/core/grid_tiles.hpp"
#include "common/core/map_io.hpp"
#include "common/core/result.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/inflation.hpp"

namespace slam::mapper {

class TileCanvas;
struct Baseline;

// One robot message as the grid needs it (the store and the DDS edge both produce this view).
struct ObservationView {
  double x = 0.0;  // sensor origin, map frame
  double y = 0.0;
  double theta = 0.0;
  bool has_heading = false;
  std::span<const Vec2> hits;    // ray end occupied
  std::span<const Vec2> misses;  // ray free, end unknown
};

struct IntegrateStats {
  uint32_t hits = 0;         // hits marked occupied
  uint32_t misses = 0;       // misses traced
  uint32_t clipped = 0;      // hits past the maximum extent: their ray was clipped, end not marked
  int64_t cells_traced = 0;  // cells visited by rays
  bool grew = false;         // layout changed (publish a snapshot)
};
// Why a point is counted in IntegrateStats::clipped, for the caller's log line.
inline constexpr const char* kClipReason = "point lies beyond the maximum map extent (max_extent_m)";

class OccupancyGrid {
 public:
  // Validates the config; the grid starts all unknown over origin + width_m x height_m.
  static Result<OccupancyGrid> create(const GridConfig& config);

  // Ray-casts every point from the sensor origin (legacy mode: marks hit cells only). Grows the grid
  // when needed. NaN/Inf, or a point farther than max_range_m, or a robot outside the maximum
  // extent: an error and the grid is untouched.
  Result<IntegrateStats> integrate(const ObservationView& obs);

  // Operator edits. obstruct grows the grid to reach the point (error past the maximum extent);
  // unobstruct returns the stored obstruction points it removed (all those in that cell).
  Status obstruct(double x, double y);
  std::vector<Vec2> unobstruct(double x, double y);
  void clear_obstructions();
  const std::vector<Vec2>& obstructions() const { return obstructions_; }

  // A prior: known pixels of the image overwrite the cells they cover (occupied -> prior_occupied,
  // free -> prior_free); the grid grows to hold it. Returns the number of cells set.
  Result<int64_t> apply_prior(const MapImage& image);
  // A compacted baseline (store_baseline.hpp): the grid grows to its layout (exactly when the resolution
  // is the same, so a rebuild goes on as the one it replaces did; within the maximum extent) and takes
  // the log-odds of its known cells, each at its centre. Returns the cells set.
  int64_t apply_baseline(const Baseline& baseline);
  // A partial re-render lands: the canvas's tiles (drawn in this layout) take its log-odds; classes,
  // inflation and dirty tiles follow cell by cell. Obstructions stay.
  void redraw(const TileCanvas& canvas);
  // Trinary export (obstructed cells count as occupied; inflation is not exported).
  MapImage to_map_image() const;

  // Tiles whose class octets changed since the last clear_dirty() (every tile after growth).
  const DirtyTiles& dirty_tiles() const { return dirty_; }
  void clear_dirty() { dirty_.clear(); }

  const GridConfig& config() const { return config_; }
  int32_t width() const { return width_; }
  int32_t height() const { return height_; }
  double resolution() const { return config_.resolution; }
  double origin_x() const { return config_.origin_x + static_cast<double>(offset_x_) * config_.resolution; }
  double origin_y() const { return config_.origin_y + static_cast<double>(offset_y_) * config_.resolution; }
  GridGeometry geometry() const { return {{origin_x(), origin_y()}, config_.resolution, width_, height_}; }
  // Increments whenever width, height or origin change.
  uint32_t layout_version() const { return layout_version_; }

  // Cell of a map-frame point; nothing when it lies outside the grid or is not finite.
  std::optional<Cell> cell_at(Vec2 p) const { return geometry().cell_at(p); }
  std::span<const uint8_t> classes() const { return classes_; }
  uint8_t cell_class(int32_t cx, int32_t cy) const { return classes_[index(cx, cy)]; }
  int16_t log_odds(int32_t cx, int32_t cy) const { return cells_[index(cx, cy)].log_odds; }
  uint16_t inflation_count(int32_t cx, int32_t cy) const { return inflation_.count(index(cx, cy)); }

 private:
  explicit OccupancyGrid(const GridConfig& config);

  size_t index(int32_t cx, int32_t cy) const {
    return static_cast<size_t>(cy) * static_cast<size_t>(width_) + static_cast<size_t>(cx);
  }
  uint8_t state_of(int32_t value) const {
    return value >= occ_ ? kCellOccupied : (value <= free_ ? kCellFree : kCellUnknown);
  }
  // Cell coordinates relative to the current grid, unbounded (may lie outside).
  double cell_x(double x) const;
  double cell_y(double y) const;

  void set_value(size_t i, int32_t value);
  void set_class(size_t i, uint8_t cls);
  void mark_dirty(size_t i);
  // Whether [bx0, bx1) x [by0, by1) united with the grid stays within the maximum extent.
  bool fits(int64_t bx0, int64_t by0, int64_t bx1, int64_t by1) const;
  // Grows to cover the box (already known to fit), padding by the growth chunk where room allows.
  void grow(int64_t bx0, int64_t by0, int64_t bx1, int64_t by1);
  // Re-lays the grid over cells [x0, x1) x [y0, y1) of the current layout (which they contain).
  void resize(int64_t x0, int64_t y0, int64_t x1, int64_t y1);
  void integrate_legacy(const ObservationView& obs, IntegrateStats* stats);
  void integrate_rays(const ObservationView& obs, IntegrateStats* stats);

  GridConfig config_;
  int32_t occ_ = 0;
  int32_t free_ = 0;
  int32_t max_side_ = 0;
  int64_t grow_chunk_ = 1;
  int32_t width_ = 0;
  int32_t height_ = 0;
  int64_t offset_x_ = 0;  // grid origin relative to config origin, in cells (no float drift)
  int64_t offset_y_ = 0;
  uint32_t layout_version_ = 0;

  // Log-odds and the observation stamp (one update per cell per observation) side by side: a ray
  // step reads both, so they share a cache line. 16-bit stamps wrap every 65535 observations, when
  // they are cleared (a negligible amortised cost).
  struct CellEvidence {
    int16_t log_odds = 0;
    uint16_t mark = 0;
  };
  std::vector<CellEvidence> cells_;
  std::vector<uint8_t> classes_;  // published as is: kept separate so snapshots are one copy
  uint16_t epoch_ = 0;
  InflationLayer inflation_;
  std::vector<Vec2> obstructions_;

  DirtyTiles dirty_;
};

}  // namespace slam::mapper

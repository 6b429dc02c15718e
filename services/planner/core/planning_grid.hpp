#pragma once
// The planner's copy of the mapper's class grid (GridSnapshot + GridTiles in map.idl), with the
// cell tests every planner shares: one octet per cell, row-major, row 0 the lowest y.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/core/cell_class.hpp"
#include "common/core/grid_tiles.hpp"
#include "common/core/result.hpp"
#include "planner/core/plan_types.hpp"

namespace slam::planner {

inline bool cell_blocked(uint8_t c) {
  return (c & kCellStateMask) == kCellOccupied || (c & (kCellInflated | kCellObstructed)) != 0;
}
inline bool cell_unknown(uint8_t c) {
  return (c & kCellStateMask) == kCellUnknown;
}
inline bool cell_free(uint8_t c) {
  return (c & kCellStateMask) == kCellFree;
}

class PlanningGrid {
 public:
  // Replaces the whole grid (a snapshot). Rejects empty or inconsistent layouts.
  Status reset(const GridGeometry& geometry, uint32_t layout_id, uint64_t version,
               std::vector<uint8_t> cells);
  // Applies a tile patch and appends the changed tiles' boxes to `changed`. Only in order
  // (version == last + 1) and for the same layout; otherwise the caller waits for the next
  // snapshot. A rejected patch changes nothing.
  Status apply_patch(uint32_t layout_id, uint64_t version, const TilePatchView& patch,
                     std::vector<CellBox>& changed);

  bool empty() const { return cells_.empty(); }
  const GridGeometry& geometry() const { return geometry_; }
  int32_t width() const { return geometry_.width; }
  int32_t height() const { return geometry_.height; }
  double resolution() const { return geometry_.resolution; }
  uint32_t layout_id() const { return layout_id_; }
  uint64_t version() const { return version_; }
  // Bumped by every reset and patch, so caches know when to refresh.
  uint64_t revision() const { return revision_; }
  const std::vector<uint8_t>& cells() const { return cells_; }

  bool contains(Cell c) const { return geometry_.contains(c); }
  size_t index(Cell c) const { return geometry_.index(c); }
  Cell cell_of(size_t index) const { return geometry_.cell_of(index); }
  uint8_t at(Cell c) const { return cells_[index(c)]; }
  bool blocked(Cell c) const { return cell_blocked(at(c)); }
  bool unknown(Cell c) const { return cell_unknown(at(c)); }
  // Blocked, or unknown when the policy forbids unknown space.
  bool impassable(Cell c, UnknownPolicy policy) const {
    const uint8_t v = at(c);
    return cell_blocked(v) || (policy == UnknownPolicy::Blocked && cell_unknown(v));
  }

  // The cell containing a map point, or nothing when the point lies outside the grid.
  std::optional<Cell> cell_at(Vec2 p) const { return geometry_.cell_at(p); }
  Vec2 centre(Cell c) const { return geometry_.centre(c); }
  // Map coordinates in cell units relative to the origin (cell (i, j) spans [i, i+1) x [j, j+1)).
  Vec2 to_grid(Vec2 p) const { return geometry_.to_grid(p); }

  // Writes the octets (for tests and tools that build grids by hand).
  void set(Cell c, uint8_t value);

 private:
  GridGeometry geometry_;
  uint32_t layout_id_ = 0;
  uint64_t version_ = 0;
  uint64_t revision_ = 0;
  std::vector<uint8_t> cells_;
};

}  // namespace slam::planner

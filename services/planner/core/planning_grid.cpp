// Snapshot and patch intake for PlanningGrid, with the checks that keep a bad message out.
#include "planner/core/planning_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace slam::planner {

namespace {
// Beyond this the grid would not fit in memory on the machines we run on (64 Gi cells).
constexpr uint64_t kMaxCells = uint64_t{1} << 36;
}  // namespace

Status PlanningGrid::reset(const GridGeometry& geometry, uint32_t layout_id, uint64_t version,
                           std::vector<uint8_t> cells) {
  if (geometry.width <= 0 || geometry.height <= 0) {
    return Error{"grid snapshot has zero width or height"};
  }
  if (geometry.cells() > kMaxCells) {
    return Error{"grid snapshot is too large: " + std::to_string(geometry.width) + "x" +
                 std::to_string(geometry.height)};
  }
  if (!std::isfinite(geometry.resolution) || geometry.resolution <= 0.0) {
    return Error{"grid snapshot resolution must be positive and finite"};
  }
  if (!std::isfinite(geometry.origin.x) || !std::isfinite(geometry.origin.y)) {
    return Error{"grid snapshot origin is not finite"};
  }
  const uint64_t expected = geometry.cells();
  if (cells.size() != expected) {
    return Error{"grid snapshot has " + std::to_string(cells.size()) + " cells, expected " +
                 std::to_string(expected)};
  }
  geometry_ = geometry;
  layout_id_ = layout_id;
  version_ = version;
  cells_ = std::move(cells);
  ++revision_;
  return Status::ok();
}

Status PlanningGrid::apply_patch(uint32_t layout_id, uint64_t version, const TilePatchView& patch,
                                 std::vector<CellBox>& changed) {
  if (empty()) return Error{"grid patch before any snapshot"};
  if (layout_id != layout_id_) {
    return Error{"grid patch for layout " + std::to_string(layout_id) + ", grid has layout " +
                 std::to_string(layout_id_)};
  }
  if (version != version_ + 1) {
    return Error{"grid patch version " + std::to_string(version) + " does not follow " +
                 std::to_string(version_)};
  }
  if (auto s = apply_tiles(patch, cells_, geometry_.width, geometry_.height, &changed); !s) return s;
  version_ = version;
  ++revision_;
  return Status::ok();
}

void PlanningGrid::set(Cell c, uint8_t value) {
  cells_[index(c)] = value;
  ++revision_;
}

}  // namespace slam::planner

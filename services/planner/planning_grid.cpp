// Snapshot and patch intake for PlanningGrid, with the checks that keep a bad message out.
#include "planner/planning_grid.hpp"

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
  if (geometry.width == 0 || geometry.height == 0) {
    return Error{"grid snapshot has zero width or height"};
  }
  if (geometry.width > static_cast<uint32_t>(INT32_MAX) ||
      geometry.height > static_cast<uint32_t>(INT32_MAX) ||
      uint64_t{geometry.width} * geometry.height > kMaxCells) {
    return Error{"grid snapshot is too large: " + std::to_string(geometry.width) + "x" +
                 std::to_string(geometry.height)};
  }
  if (!std::isfinite(geometry.resolution) || geometry.resolution <= 0.0) {
    return Error{"grid snapshot resolution must be positive and finite"};
  }
  if (!std::isfinite(geometry.origin.x) || !std::isfinite(geometry.origin.y)) {
    return Error{"grid snapshot origin is not finite"};
  }
  const uint64_t expected = uint64_t{geometry.width} * geometry.height;
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

Status PlanningGrid::apply_patch(uint32_t layout_id, uint64_t version, const CellBox& box,
                                 std::span<const uint8_t> cells) {
  if (empty()) return Error{"grid patch before any snapshot"};
  if (layout_id != layout_id_) {
    return Error{"grid patch for layout " + std::to_string(layout_id) + ", grid has layout " +
                 std::to_string(layout_id_)};
  }
  if (version != version_ + 1) {
    return Error{"grid patch version " + std::to_string(version) + " does not follow " +
                 std::to_string(version_)};
  }
  if (uint64_t{box.x0} + box.width > geometry_.width || uint64_t{box.y0} + box.height > geometry_.height) {
    return Error{"grid patch box exceeds the grid"};
  }
  if (cells.size() != uint64_t{box.width} * box.height) {
    return Error{"grid patch has " + std::to_string(cells.size()) + " cells, box holds " +
                 std::to_string(uint64_t{box.width} * box.height)};
  }
  for (uint32_t row = 0; row < box.height; ++row) {
    const uint8_t* src = cells.data() + static_cast<size_t>(row) * box.width;
    uint8_t* dst = cells_.data() + static_cast<size_t>(box.y0 + row) * geometry_.width + box.x0;
    std::copy(src, src + box.width, dst);
  }
  version_ = version;
  ++revision_;
  return Status::ok();
}

std::optional<Cell> PlanningGrid::cell_at(Vec2 p) const {
  if (empty() || !std::isfinite(p.x) || !std::isfinite(p.y)) return std::nullopt;
  const Vec2 g = to_grid(p);
  if (g.x < 0.0 || g.y < 0.0 || g.x >= geometry_.width || g.y >= geometry_.height) {
    return std::nullopt;
  }
  const Cell c{static_cast<int32_t>(g.x), static_cast<int32_t>(g.y)};
  return contains(c) ? std::optional<Cell>{c} : std::nullopt;
}

Vec2 PlanningGrid::centre(Cell c) const {
  return Vec2{geometry_.origin.x + (c.x + 0.5) * geometry_.resolution,
              geometry_.origin.y + (c.y + 0.5) * geometry_.resolution};
}

Vec2 PlanningGrid::to_grid(Vec2 p) const {
  return Vec2{(p.x - geometry_.origin.x) / geometry_.resolution,
              (p.y - geometry_.origin.y) / geometry_.resolution};
}

void PlanningGrid::set(Cell c, uint8_t value) {
  cells_[index(c)] = value;
  ++revision_;
}

}  // namespace slam::planner

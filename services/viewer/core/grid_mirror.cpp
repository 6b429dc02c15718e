// Snapshot + in-order patch application with a dirty box (see grid_mirror.hpp).
#include "viewer/core/grid_mirror.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "viewer/core/cell_colors.hpp"

namespace slam::viewer {
namespace {

bool known(uint8_t cell) {
  const uint8_t state = cell & kCellStateMask;
  return state == kCellFree || state == kCellOccupied;
}

}  // namespace

void CellBox::unite(const CellBox& o) {
  if (o.empty()) return;
  if (empty()) {
    *this = o;
    return;
  }
  const uint32_t x1 = std::max(x0 + width, o.x0 + o.width), y1 = std::max(y0 + height, o.y0 + o.height);
  x0 = std::min(x0, o.x0);
  y0 = std::min(y0, o.y0);
  width = x1 - x0;
  height = y1 - y0;
}

Status GridMirror::apply_snapshot(GridSnapshotData&& s) {
  const uint64_t expected = uint64_t{s.info.width} * s.info.height;
  if (s.info.width == 0 || s.info.height == 0) return Error{"grid snapshot has zero width or height"};
  if (s.cells.size() != expected)
    return Error{"grid snapshot has " + std::to_string(s.cells.size()) + " cells, expected " +
                 std::to_string(expected)};
  if (!(s.info.resolution > 0.0) || !std::isfinite(s.info.resolution))
    return Error{"grid snapshot resolution must be positive"};
  layout_changed_ = layout_changed_ || !has_grid_ || s.info.width != info_.width ||
                    s.info.height != info_.height || s.layout_id != layout_id_ ||
                    s.info.resolution != info_.resolution || s.info.origin.x != info_.origin.x ||
                    s.info.origin.y != info_.origin.y;
  has_grid_ = true;
  waiting_ = false;
  layout_id_ = s.layout_id;
  version_ = s.version;
  info_ = s.info;
  cells_ = std::move(s.cells);
  dirty_ = {0, 0, info_.width, info_.height};
  known_ = {};
  include_known(dirty_);
  return {};
}

PatchResult GridMirror::apply_patch(const GridPatchData& p) {
  if (!has_grid_) return PatchResult::NoGrid;
  if (p.layout_id != layout_id_) {
    waiting_ = true;
    return PatchResult::WrongLayout;
  }
  if (p.version <= version_) return PatchResult::Stale;
  if (waiting_ || p.version != version_ + 1) {
    waiting_ = true;
    return PatchResult::Gap;
  }
  if (uint64_t{p.x0} + p.width > info_.width || uint64_t{p.y0} + p.height > info_.height ||
      p.cells.size() != uint64_t{p.width} * p.height)
    return PatchResult::Invalid;
  for (uint32_t row = 0; row < p.height; ++row)
    std::copy_n(p.cells.begin() + static_cast<std::ptrdiff_t>(size_t{row} * p.width), p.width,
                cells_.begin() + static_cast<std::ptrdiff_t>((size_t{p.y0} + row) * info_.width + p.x0));
  version_ = p.version;
  dirty_.unite({p.x0, p.y0, p.width, p.height});
  include_known({p.x0, p.y0, p.width, p.height});
  return PatchResult::Applied;
}

WorldBox GridMirror::bounds() const {
  return {info_.origin.x, info_.origin.y, info_.origin.x + info_.width * info_.resolution,
          info_.origin.y + info_.height * info_.resolution};
}

void GridMirror::include_known(const CellBox& area) {
  // Per row only the first and last known cell matter: one pass, no allocation.
  for (uint32_t y = area.y0; y < area.y0 + area.height; ++y) {
    const uint8_t* row = cells_.data() + size_t{y} * info_.width;
    uint32_t first = area.x0, last = area.x0 + area.width;
    while (first < last && !known(row[first])) ++first;
    if (first == last) continue;
    while (!known(row[last - 1])) --last;
    known_.unite({first, y, last - first, 1});
  }
}

bool GridMirror::known_bounds(WorldBox* box) const {
  if (!has_grid_ || known_.empty()) return false;
  const double r = info_.resolution;
  *box = {info_.origin.x + known_.x0 * r, info_.origin.y + known_.y0 * r,
          info_.origin.x + (known_.x0 + known_.width) * r, info_.origin.y + (known_.y0 + known_.height) * r};
  return true;
}

bool GridMirror::cell_at(Vec2 w, uint8_t* cell) const {
  if (!has_grid_) return false;
  const double fx = std::floor((w.x - info_.origin.x) / info_.resolution);
  const double fy = std::floor((w.y - info_.origin.y) / info_.resolution);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < info_.width && fy < info_.height)) return false;
  *cell = cells_[static_cast<size_t>(fy) * info_.width + static_cast<size_t>(fx)];
  return true;
}

CellBox GridMirror::take_dirty() {
  return std::exchange(dirty_, CellBox{});
}

bool GridMirror::take_layout_changed() {
  return std::exchange(layout_changed_, false);
}

}  // namespace slam::viewer

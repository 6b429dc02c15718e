// Snapshot + in-order patch application with a dirty box (see grid_mirror.hpp).
#include "viewer/core/grid_mirror.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/core/grid_tiles.hpp"
#include "viewer/core/cell_colors.hpp"

namespace slam::viewer {
namespace {

bool known(uint8_t cell) {
  const uint8_t state = cell & kCellStateMask;
  return state == kCellFree || state == kCellOccupied;
}

}  // namespace

Status GridMirror::apply_snapshot(msg::GridSnapshot&& s) {
  const uint64_t expected = uint64_t{s.info.width} * s.info.height;
  if (s.info.width == 0 || s.info.height == 0) return Error{"grid snapshot has zero width or height"};
  if (s.info.width > static_cast<uint32_t>(INT32_MAX) || s.info.height > static_cast<uint32_t>(INT32_MAX))
    return Error{"grid snapshot is too large: " + std::to_string(s.info.width) + "x" +
                 std::to_string(s.info.height)};
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
  geometry_ = {info_.origin, info_.resolution, static_cast<int32_t>(info_.width),
               static_cast<int32_t>(info_.height)};
  cells_ = std::move(s.cells);
  dirty_ = {0, 0, geometry_.width, geometry_.height};
  known_ = {};
  include_known(dirty_);
  return {};
}

PatchResult GridMirror::apply_patch(const msg::GridTiles& p) {
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
  changed_.clear();
  const TilePatchView view{p.tile_side, p.encoding, p.tiles, p.data};
  if (!apply_tiles(view, cells_, geometry_.width, geometry_.height, &changed_)) return PatchResult::Invalid;
  version_ = p.version;
  for (const CellBox& box : changed_) {
    dirty_.unite(box);
    include_known(box);
  }
  return PatchResult::Applied;
}

WorldBox GridMirror::bounds() const {
  const Vec2 top_right = geometry_.corner({geometry_.width, geometry_.height});
  return {geometry_.origin.x, geometry_.origin.y, top_right.x, top_right.y};
}

void GridMirror::include_known(const CellBox& area) {
  // Per row only the first and last known cell matter: one pass, no allocation.
  for (int32_t y = area.y0; y < area.y0 + area.height; ++y) {
    const uint8_t* row = cells_.data() + geometry_.index({0, y});
    int32_t first = area.x0, last = area.x0 + area.width;
    while (first < last && !known(row[first])) ++first;
    if (first == last) continue;
    while (!known(row[last - 1])) --last;
    known_.unite({first, y, last - first, 1});
  }
}

std::optional<WorldBox> GridMirror::known_bounds() const {
  if (!has_grid_ || known_.empty()) return std::nullopt;
  const Vec2 lo = geometry_.corner({known_.x0, known_.y0});
  const Vec2 hi = geometry_.corner({known_.x0 + known_.width, known_.y0 + known_.height});
  return WorldBox{lo.x, lo.y, hi.x, hi.y};
}

std::optional<uint8_t> GridMirror::cell_at(Vec2 w) const {
  if (!has_grid_) return std::nullopt;
  const auto c = geometry_.cell_at(w);
  if (!c) return std::nullopt;
  return cells_[geometry_.index(*c)];
}

CellBox GridMirror::take_dirty() {
  return std::exchange(dirty_, CellBox{});
}

bool GridMirror::take_layout_changed() {
  return std::exchange(layout_changed_, false);
}

}  // namespace slam::viewer

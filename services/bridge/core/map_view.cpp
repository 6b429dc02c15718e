// The bridge's grid copy (see map_view.hpp).
#include "bridge/core/map_view.hpp"

#include <string>

#include "common/core/grid_tiles.hpp"

namespace slam::bridge {

Status MapView::ingest(msg::GridSnapshot&& s) {
  const GridGeometry g{s.info.origin, s.info.resolution, static_cast<int32_t>(s.info.width),
                       static_cast<int32_t>(s.info.height)};
  if (g.width <= 0 || g.height <= 0 || s.cells.size() != g.cells())
    return Error{"snapshot of " + std::to_string(s.cells.size()) + " cells for a " + std::to_string(g.width) +
                 " x " + std::to_string(g.height) + " grid"};
  has_grid_ = true;
  layout_id_ = s.layout_id;
  version_ = s.version;
  stamp_ns_ = s.stamp_ns;
  geometry_ = g;
  cells_ = std::move(s.cells);
  changed_ = CellBox{0, 0, g.width, g.height};
  ++revision_;
  return {};
}

Status MapView::ingest(const msg::GridTiles& t) {
  if (!has_grid_ || t.layout_id != layout_id_ || t.version != version_ + 1)
    return Error{"patch " + std::to_string(t.version) + " does not follow grid version " +
                 std::to_string(version_) + ": waiting for the next snapshot"};
  TilePatchView patch;
  patch.side = t.tile_side;
  patch.encoding = t.encoding;
  patch.tiles = t.tiles;
  patch.data = t.data;
  scratch_.clear();
  SLAM_TRY(apply_tiles(patch, cells_, geometry_.width, geometry_.height, &scratch_));
  version_ = t.version;
  stamp_ns_ = t.stamp_ns;
  for (const CellBox& box : scratch_) changed_.unite(box);
  ++revision_;
  return {};
}

CellBox MapView::take_changed() {
  const CellBox out = changed_;
  changed_ = CellBox{};
  return out;
}

}  // namespace slam::bridge

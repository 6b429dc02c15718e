#pragma once
// The occupancy grid as a DDS receiver rebuilds it: one GridSnapshot plus the GridTiles patches
// that follow it version by version. Integration tests check the mapper's output through this, the
// way the planner, viewer and bridge see it. Header-only; needs the generated IDL types.
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "common/core/grid_tiles.hpp"
#include "common/fastdds/fast_topics.hpp"

namespace slam::testkit {

struct ReceivedMap {
  uint32_t layout_id = 0;
  uint64_t version = 0;
  GridInfo info;
  std::vector<uint8_t> cells;

  uint8_t at(double x, double y) const {  // the cell holding map-frame point (x, y); 0xff outside
    const auto cx = static_cast<int64_t>(std::floor((x - info.origin().x()) / info.resolution()));
    const auto cy = static_cast<int64_t>(std::floor((y - info.origin().y()) / info.resolution()));
    if (cx < 0 || cy < 0 || cx >= info.width() || cy >= info.height()) return 0xff;
    return cells[static_cast<size_t>(cy) * info.width() + static_cast<size_t>(cx)];
  }
  uint8_t state(double x, double y) const { return static_cast<uint8_t>(at(x, y) & CELL_STATE_MASK); }
  // The same for a test's own point type (anything with x and y members).
  template <class Point>
  uint8_t state(const Point& p) const {
    return state(p.x, p.y);
  }
};

// `snapshot` with every patch of its layout applied in version order, stopping at the first gap
// (a receiver cannot skip a version) or at a patch that does not decode.
inline ReceivedMap assemble(const GridSnapshot& snapshot, const std::vector<GridTiles>& patches) {
  ReceivedMap m{snapshot.layout_id(), snapshot.version(), snapshot.info(), snapshot.cells()};
  std::map<uint64_t, const GridTiles*> later;
  for (const GridTiles& p : patches)
    if (p.layout_id() == m.layout_id && p.version() > m.version) later[p.version()] = &p;
  for (const auto& [version, p] : later) {
    if (version != m.version + 1) break;
    const TilePatchView view{p->tile_side(), p->encoding(), p->tiles(), p->data()};
    if (!apply_tiles(view, m.cells, static_cast<int32_t>(m.info.width()),
                     static_cast<int32_t>(m.info.height())))
      break;
    m.version = version;
  }
  return m;
}

}  // namespace slam::testkit

#include "bridge/core/map_view.hpp"

#include <gtest/gtest.h>

#include "common/core/cell_class.hpp"
#include "common/core/grid_tiles.hpp"

namespace slam::bridge {
namespace {

msg::GridSnapshot snapshot(int32_t w, int32_t h, uint64_t version) {
  msg::GridSnapshot s;
  s.layout_id = 1;
  s.version = version;
  s.info = msg::GridInfo{static_cast<uint32_t>(w), static_cast<uint32_t>(h), 0.1, {0.0, 0.0}, 0.0};
  s.cells.assign(static_cast<size_t>(w * h), kCellUnknown);
  return s;
}

// A patch that marks cell (x, y) occupied on a w x h grid, as the mapper would encode it.
msg::GridTiles patch(std::vector<uint8_t> cells, int32_t w, int32_t h, int32_t x, int32_t y,
                     uint64_t version) {
  cells[static_cast<size_t>(y * w + x)] = kCellOccupied;
  DirtyTiles dirty;
  dirty.reset(TileLayout{w, h, 32});
  dirty.mark(x, y);
  EncodedTiles encoded;
  encode_tiles(cells, dirty, encoded);
  return msg::GridTiles{1,           version, 0, 32, static_cast<uint8_t>(encoded.encoding), encoded.tiles,
                        encoded.data};
}

TEST(MapView, ASnapshotChangesTheWholeGrid) {
  MapView map;
  EXPECT_FALSE(map.has_grid());
  ASSERT_TRUE(map.ingest(snapshot(64, 40, 3)));
  EXPECT_TRUE(map.has_grid());
  EXPECT_EQ(map.take_changed(), (CellBox{0, 0, 64, 40}));
  EXPECT_TRUE(map.take_changed().empty());
}

TEST(MapView, AppliesTheNextPatchAndReportsItsTile) {
  MapView map;
  ASSERT_TRUE(map.ingest(snapshot(64, 40, 3)));
  map.take_changed();
  const uint64_t revision = map.revision();
  const std::vector<uint8_t> cells(map.cells().begin(), map.cells().end());
  ASSERT_TRUE(map.ingest(patch(cells, 64, 40, 40, 5, 4)));
  EXPECT_EQ(map.cells()[5 * 64 + 40], kCellOccupied);
  EXPECT_EQ(map.take_changed(), (CellBox{32, 0, 32, 32}));
  EXPECT_GT(map.revision(), revision);
}

TEST(MapView, SkipsAPatchThatDoesNotFollow) {
  MapView map;
  ASSERT_TRUE(map.ingest(snapshot(64, 40, 3)));
  map.take_changed();
  const std::vector<uint8_t> cells(map.cells().begin(), map.cells().end());
  EXPECT_FALSE(map.ingest(patch(cells, 64, 40, 1, 1, 5)));  // version 4 is missing
  EXPECT_EQ(map.cells()[1 * 64 + 1], kCellUnknown);
  EXPECT_TRUE(map.take_changed().empty());
}

TEST(MapView, RefusesASnapshotWhoseCellsDoNotFitItsSize) {
  MapView map;
  msg::GridSnapshot s = snapshot(10, 10, 1);
  s.cells.pop_back();
  EXPECT_FALSE(map.ingest(std::move(s)));
  EXPECT_FALSE(map.has_grid());
}

}  // namespace
}  // namespace slam::bridge

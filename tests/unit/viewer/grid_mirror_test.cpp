// Snapshot and patch application: in-order patches update the cells and the dirty box; stale,
// gapped, mis-laid-out and malformed patches do not; a stream with a lost patch ends equal to its
// source once the next snapshot arrives.
#include "viewer/core/grid_mirror.hpp"

#include <gtest/gtest.h>

#include "common/core/grid_tiles.hpp"
#include "random_tile_source.hpp"

namespace slam::viewer {
namespace {

msg::GridSnapshot snapshot(uint32_t layout, uint64_t version, uint32_t w = 4, uint32_t h = 3) {
  msg::GridSnapshot s;
  s.layout_id = layout;
  s.version = version;
  s.info = {w, h, 0.5, {-1.0, -2.0}, 0.2};
  s.cells.assign(size_t{w} * h, 0);
  return s;
}

// Every cell of the box set to v, in tiles of one cell on a grid 4 cells wide.
msg::GridTiles patch(uint32_t layout, uint64_t version, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h,
                     uint8_t v) {
  msg::GridTiles p{layout, version, 0, 1, static_cast<uint8_t>(TileEncoding::Raw), {}, {}};
  for (uint32_t y = y0; y < y0 + h; ++y)
    for (uint32_t x = x0; x < x0 + w; ++x) p.tiles.push_back(y * 4 + x);
  p.data.assign(p.tiles.size(), v);
  return p;
}

TEST(GridMirror, SnapshotReplacesAndMarksEverythingDirty) {
  GridMirror m;
  ASSERT_TRUE(m.apply_snapshot(snapshot(7, 10)));
  EXPECT_TRUE(m.take_layout_changed());
  EXPECT_FALSE(m.take_layout_changed());
  const CellBox d = m.take_dirty();
  EXPECT_EQ(d, (CellBox{0, 0, 4, 3}));
  EXPECT_TRUE(m.take_dirty().empty());
  const WorldBox b = m.bounds();
  EXPECT_DOUBLE_EQ(b.min_x, -1.0);
  EXPECT_DOUBLE_EQ(b.max_x, 1.0);
  EXPECT_DOUBLE_EQ(b.max_y, -0.5);
}

TEST(GridMirror, KnownBoundsCoverFreeAndOccupiedCellsAndGrowWithPatches) {
  GridMirror m;
  EXPECT_FALSE(m.known_bounds());
  auto s = snapshot(1, 1);     // 4 x 3 cells of 0.5 m from (-1, -2)
  s.cells[1 * 4 + 1] = 1;      // free at (1, 1)
  s.cells[1 * 4 + 2] = 2 | 4;  // occupied + inflated at (2, 1)
  s.cells[2 * 4 + 3] = 3;      // state 3 is not a known state
  ASSERT_TRUE(m.apply_snapshot(std::move(s)));
  auto b = m.known_bounds();
  ASSERT_TRUE(b);
  EXPECT_DOUBLE_EQ(b->min_x, -0.5);
  EXPECT_DOUBLE_EQ(b->max_x, 0.5);
  EXPECT_DOUBLE_EQ(b->min_y, -1.5);
  EXPECT_DOUBLE_EQ(b->max_y, -1.0);
  ASSERT_EQ(m.apply_patch(patch(1, 2, 0, 0, 1, 1, 1)), PatchResult::Applied);
  b = m.known_bounds();
  ASSERT_TRUE(b);
  EXPECT_DOUBLE_EQ(b->min_x, -1.0);
  EXPECT_DOUBLE_EQ(b->min_y, -2.0);
  EXPECT_DOUBLE_EQ(b->max_x, 0.5);
  // A new snapshot with nothing known forgets it.
  ASSERT_TRUE(m.apply_snapshot(snapshot(1, 5)));
  EXPECT_FALSE(m.known_bounds());
}

TEST(GridMirror, RejectsMalformedSnapshots) {
  GridMirror m;
  auto bad = snapshot(1, 1);
  bad.cells.pop_back();
  EXPECT_FALSE(m.apply_snapshot(std::move(bad)));
  auto zero = snapshot(1, 1);
  zero.info.resolution = 0.0;
  EXPECT_FALSE(m.apply_snapshot(std::move(zero)));
  EXPECT_FALSE(m.has_grid());
}

TEST(GridMirror, InOrderPatchesApplyAndUniteDirtyBoxes) {
  GridMirror m;
  ASSERT_TRUE(m.apply_snapshot(snapshot(7, 10)));
  m.take_dirty();
  EXPECT_EQ(m.apply_patch(patch(7, 11, 1, 1, 2, 1, 2)), PatchResult::Applied);
  EXPECT_EQ(m.apply_patch(patch(7, 12, 3, 2, 1, 1, 1)), PatchResult::Applied);
  EXPECT_EQ(m.cells()[1 * 4 + 1], 2);
  EXPECT_EQ(m.cells()[1 * 4 + 2], 2);
  EXPECT_EQ(m.cells()[2 * 4 + 3], 1);
  const CellBox d = m.take_dirty();
  EXPECT_EQ(d, (CellBox{1, 1, 3, 2}));
  EXPECT_EQ(m.cell_at({-1.0 + 0.5 * 3.2, -2.0 + 0.5 * 2.1}), std::optional<uint8_t>{1});
  EXPECT_FALSE(m.cell_at({5.0, 5.0}));
}

TEST(GridMirror, StaleGapAndLayoutChangesAreNotApplied) {
  GridMirror m;
  EXPECT_EQ(m.apply_patch(patch(7, 1, 0, 0, 1, 1, 2)), PatchResult::NoGrid);
  ASSERT_TRUE(m.apply_snapshot(snapshot(7, 10)));
  EXPECT_EQ(m.apply_patch(patch(7, 10, 0, 0, 1, 1, 2)), PatchResult::Stale);
  EXPECT_EQ(m.apply_patch(patch(8, 11, 0, 0, 1, 1, 2)), PatchResult::WrongLayout);
  EXPECT_TRUE(m.waiting_for_snapshot());
  EXPECT_EQ(m.apply_patch(patch(7, 11, 0, 0, 1, 1, 2)), PatchResult::Gap);  // still waiting
  EXPECT_EQ(m.cells()[0], 0);
  ASSERT_TRUE(m.apply_snapshot(snapshot(7, 20)));
  EXPECT_EQ(m.apply_patch(patch(7, 22, 0, 0, 1, 1, 2)), PatchResult::Gap);
}

TEST(GridMirror, MalformedPatchIsInvalidAndChangesNothing) {
  GridMirror m;
  ASSERT_TRUE(m.apply_snapshot(snapshot(7, 10)));
  auto outside = patch(7, 11, 3, 2, 1, 1, 2);
  outside.tiles = {11, 12};  // 12 cells: tile 12 lies past the grid
  outside.data = {2, 2};
  EXPECT_EQ(m.apply_patch(outside), PatchResult::Invalid);
  auto short_cells = patch(7, 11, 0, 0, 2, 2, 2);
  short_cells.data.pop_back();
  EXPECT_EQ(m.apply_patch(short_cells), PatchResult::Invalid);
  EXPECT_EQ(m.version(), 10u);
  EXPECT_EQ(m.cells(), std::vector<uint8_t>(12, 0));
}

// The mapper's side played with the shared codec: a 70 x 45 grid (edge tiles clipped) changes at
// random, one patch per period; patch 4 is lost. The mirror stops at the gap, waits, and equals
// the source cell for cell after the next snapshot and the patches that follow it.
TEST(GridMirror, StreamWithALostPatchEqualsTheSourceAfterTheNextSnapshot) {
  constexpr int32_t kW = 70, kH = 45;
  testkit::RandomTileSource source(kW, kH, 0, 11);
  const auto next_patch = [&](uint64_t version) {
    const EncodedTiles& encoded = source.next_patch();
    return msg::GridTiles{
        3, version, 0, kGridTileSide, static_cast<uint8_t>(encoded.encoding), encoded.tiles, encoded.data};
  };
  const auto source_snapshot = [&](uint64_t version) {
    msg::GridSnapshot s = snapshot(3, version, kW, kH);
    s.cells = source.cells();
    return s;
  };
  GridMirror m;
  ASSERT_TRUE(m.apply_snapshot(source_snapshot(0)));
  for (uint64_t v = 1; v <= 3; ++v) ASSERT_EQ(m.apply_patch(next_patch(v)), PatchResult::Applied);
  EXPECT_EQ(m.cells(), source.cells());
  (void)next_patch(4);  // lost
  EXPECT_EQ(m.apply_patch(next_patch(5)), PatchResult::Gap);
  EXPECT_EQ(m.apply_patch(next_patch(6)), PatchResult::Gap);
  EXPECT_TRUE(m.waiting_for_snapshot());
  EXPECT_NE(m.cells(), source.cells());
  ASSERT_TRUE(m.apply_snapshot(source_snapshot(6)));
  for (uint64_t v = 7; v <= 9; ++v) ASSERT_EQ(m.apply_patch(next_patch(v)), PatchResult::Applied);
  EXPECT_EQ(m.cells(), source.cells());
}

}  // namespace
}  // namespace slam::viewer

// Snapshot and patch application: in-order patches update the cells and the dirty box; stale,
// gapped, mis-laid-out and malformed patches do not.
#include "viewer/core/grid_mirror.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

GridSnapshotData snapshot(uint32_t layout, uint64_t version, uint32_t w = 4, uint32_t h = 3) {
  GridSnapshotData s;
  s.layout_id = layout;
  s.version = version;
  s.info = {w, h, 0.5, {-1.0, -2.0}, 0.2};
  s.cells.assign(size_t{w} * h, 0);
  return s;
}

GridPatchData patch(uint32_t layout, uint64_t version, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h,
                    uint8_t v) {
  return {layout, version, x0, y0, w, h, std::vector<uint8_t>(size_t{w} * h, v)};
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

TEST(GridMirror, PatchOutsideGridIsInvalid) {
  GridMirror m;
  ASSERT_TRUE(m.apply_snapshot(snapshot(7, 10)));
  EXPECT_EQ(m.apply_patch(patch(7, 11, 3, 0, 2, 1, 2)), PatchResult::Invalid);
  auto short_cells = patch(7, 11, 0, 0, 2, 2, 2);
  short_cells.cells.pop_back();
  EXPECT_EQ(m.apply_patch(short_cells), PatchResult::Invalid);
  EXPECT_EQ(m.version(), 10u);
}

}  // namespace
}  // namespace slam::viewer

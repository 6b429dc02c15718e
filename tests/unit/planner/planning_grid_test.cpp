// PlanningGrid: snapshot and patch intake, coordinate conversion, cell classes.
#include "planner/core/planning_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grid_builder.hpp"
#include "random_tile_source.hpp"

namespace slam::planner {
namespace {

TEST(PlanningGrid, RejectsBadSnapshots) {
  PlanningGrid g;
  EXPECT_FALSE(g.reset({{}, 0.1, 0, 4}, 1, 0, {}));
  EXPECT_FALSE(g.reset({{}, 0.0, 2, 2}, 1, 0, std::vector<uint8_t>(4)));
  EXPECT_FALSE(g.reset({{std::nan(""), 0}, 0.1, 2, 2}, 1, 0, std::vector<uint8_t>(4)));
  const Status s = g.reset({{}, 0.1, 2, 2}, 1, 0, std::vector<uint8_t>(3));
  EXPECT_FALSE(s);
  EXPECT_NE(s.message().find("3 cells, expected 4"), std::string::npos);
  EXPECT_TRUE(g.empty());
}

TEST(PlanningGrid, AppliesPatchesInOrderOnly) {
  PlanningGrid g = test::uniform_grid(4, 3, kCellUnknown);
  const uint64_t rev = g.revision();
  // 2 x 2 tiles on a 4 x 3 grid: tile 3 is the clipped top-right one, cells (2..3, 2).
  const std::vector<uint32_t> tile3{3};
  const std::vector<uint8_t> cells{kCellFree, kCellOccupied};
  const auto patch = [](std::span<const uint32_t> tiles, std::span<const uint8_t> data) {
    return TilePatchView{2, static_cast<uint8_t>(TileEncoding::Raw), tiles, data};
  };
  std::vector<CellBox> changed;
  ASSERT_TRUE(g.apply_patch(1, 1, patch(tile3, cells), changed));
  EXPECT_EQ(g.at({2, 2}), kCellFree);
  EXPECT_EQ(g.at({3, 2}), kCellOccupied);
  EXPECT_EQ(g.at({0, 0}), kCellUnknown);
  EXPECT_EQ(changed, (std::vector<CellBox>{{2, 2, 2, 1}}));
  EXPECT_GT(g.revision(), rev);
  EXPECT_FALSE(g.apply_patch(1, 3, patch(tile3, cells), changed));                     // gap
  EXPECT_FALSE(g.apply_patch(2, 2, patch(tile3, cells), changed));                     // layout
  EXPECT_FALSE(g.apply_patch(1, 2, patch(std::vector<uint32_t>{4}, cells), changed));  // outside
  EXPECT_FALSE(g.apply_patch(1, 2, patch(tile3, std::vector<uint8_t>{1}), changed));   // size
  EXPECT_EQ(g.version(), 1u);
  EXPECT_TRUE(g.apply_patch(1, 2, patch(tile3, cells), changed));
  EXPECT_EQ(g.version(), 2u);
}

// The mapper's side played with the shared codec: a 70 x 45 grid (edge tiles clipped) changes at
// random, one patch per period; patch 4 is lost. The grid refuses the gap and equals the source
// cell for cell after the next snapshot and the patches that follow it.
TEST(PlanningGrid, StreamWithALostPatchEqualsTheSourceAfterTheNextSnapshot) {
  constexpr int32_t kW = 70, kH = 45;
  const GridGeometry geometry{{0.0, 0.0}, 0.1, kW, kH};
  testkit::RandomTileSource source(kW, kH, kCellUnknown, 5);
  const auto next_patch = [&] {
    const EncodedTiles& encoded = source.next_patch();
    return TilePatchView{kGridTileSide, static_cast<uint8_t>(encoded.encoding), encoded.tiles, encoded.data};
  };
  PlanningGrid g;
  ASSERT_TRUE(g.reset(geometry, 3, 0, source.cells()));
  std::vector<CellBox> changed;
  for (uint64_t v = 1; v <= 3; ++v) ASSERT_TRUE(g.apply_patch(3, v, next_patch(), changed));
  EXPECT_EQ(g.cells(), source.cells());
  (void)next_patch();  // version 4, lost
  const Status gap = g.apply_patch(3, 5, next_patch(), changed);
  ASSERT_FALSE(gap);
  EXPECT_NE(gap.message().find("does not follow 3"), std::string::npos) << gap.message();
  (void)next_patch();  // version 6, skipped while waiting for the snapshot
  ASSERT_TRUE(g.reset(geometry, 3, 6, source.cells()));
  for (uint64_t v = 7; v <= 9; ++v) ASSERT_TRUE(g.apply_patch(3, v, next_patch(), changed));
  EXPECT_EQ(g.cells(), source.cells());
}

TEST(PlanningGrid, ConvertsCoordinates) {
  PlanningGrid g;
  ASSERT_TRUE(g.reset({{-1.0, 2.0}, 0.5, 10, 5}, 1, 0, std::vector<uint8_t>(50, kCellFree)));
  EXPECT_EQ(g.cell_at({-1.0, 2.0}).value(), (Cell{0, 0}));
  EXPECT_EQ(g.cell_at({3.99, 4.49}).value(), (Cell{9, 4}));
  EXPECT_FALSE(g.cell_at({4.0, 3.0}));
  EXPECT_FALSE(g.cell_at({-1.01, 3.0}));
  EXPECT_FALSE(g.cell_at({std::numeric_limits<double>::infinity(), 3.0}));
  EXPECT_DOUBLE_EQ(g.centre({1, 1}).x, -0.25);
  EXPECT_DOUBLE_EQ(g.centre({1, 1}).y, 2.75);
}

TEST(PlanningGrid, ClassifiesCells) {
  EXPECT_TRUE(cell_blocked(kCellOccupied));
  EXPECT_TRUE(cell_blocked(kCellFree | kCellInflated));
  EXPECT_TRUE(cell_blocked(kCellFree | kCellObstructed));
  EXPECT_TRUE(cell_blocked(kCellUnknown | kCellInflated));
  EXPECT_FALSE(cell_blocked(kCellFree));
  EXPECT_FALSE(cell_blocked(kCellUnknown));
  PlanningGrid g = test::grid_from_art({"?."});
  EXPECT_TRUE(g.impassable({0, 0}, UnknownPolicy::Blocked));
  EXPECT_FALSE(g.impassable({0, 0}, UnknownPolicy::Allowed));
}

}  // namespace
}  // namespace slam::planner

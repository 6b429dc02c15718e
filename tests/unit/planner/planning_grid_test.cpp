// PlanningGrid: snapshot and patch intake, coordinate conversion, cell classes.
#include "planner/planning_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grid_builder.hpp"

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
  const std::vector<uint8_t> box{kCellFree, kCellOccupied, kCellFree, kCellFree};
  ASSERT_TRUE(g.apply_patch(1, 1, CellBox{1, 1, 2, 2}, box));
  EXPECT_EQ(g.at({1, 1}), kCellFree);
  EXPECT_EQ(g.at({2, 1}), kCellOccupied);
  EXPECT_EQ(g.at({1, 2}), kCellFree);
  EXPECT_EQ(g.at({0, 0}), kCellUnknown);
  EXPECT_GT(g.revision(), rev);
  EXPECT_FALSE(g.apply_patch(1, 3, CellBox{0, 0, 1, 1}, std::vector<uint8_t>{1}));     // gap
  EXPECT_FALSE(g.apply_patch(2, 2, CellBox{0, 0, 1, 1}, std::vector<uint8_t>{1}));     // layout
  EXPECT_FALSE(g.apply_patch(1, 2, CellBox{3, 0, 2, 1}, std::vector<uint8_t>{1, 1}));  // outside
  EXPECT_FALSE(g.apply_patch(1, 2, CellBox{0, 0, 2, 1}, std::vector<uint8_t>{1}));     // size
  EXPECT_TRUE(g.apply_patch(1, 2, CellBox{0, 0, 1, 1}, std::vector<uint8_t>{kCellFree}));
  EXPECT_EQ(g.version(), 2u);
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

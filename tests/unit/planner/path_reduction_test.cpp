// Supercover walks, line of sight and path reduction.
#include "planner/core/path_reduction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "grid_builder.hpp"
#include "planner/core/grid_astar.hpp"
#include "planner/core/line_of_sight.hpp"

namespace slam::planner {
namespace {

std::vector<Cell> walk(Vec2 a, Vec2 b) {
  std::vector<Cell> cells;
  walk_segment(a, b, [&](Cell c, double) {
    cells.push_back(c);
    return true;
  });
  return cells;
}

bool has(const std::vector<Cell>& cells, Cell c) {
  return std::find(cells.begin(), cells.end(), c) != cells.end();
}

TEST(LineOfSight, WalksEveryTouchedCell) {
  const auto straight = walk({0.5, 0.5}, {3.5, 0.5});
  EXPECT_EQ(straight.size(), 4u);
  const auto shallow = walk({0.5, 0.5}, {3.5, 1.5});
  EXPECT_TRUE(has(shallow, {1, 0}));
  EXPECT_TRUE(has(shallow, {2, 1}));
  EXPECT_TRUE(has(shallow, {3, 1}));
  // Exactly through a corner: both side cells count (supercover).
  const auto diagonal = walk({0.5, 0.5}, {1.5, 1.5});
  EXPECT_EQ(diagonal.size(), 4u);
  EXPECT_TRUE(has(diagonal, {1, 0}));
  EXPECT_TRUE(has(diagonal, {0, 1}));
  const auto backwards = walk({3.5, 2.5}, {0.5, 0.5});
  EXPECT_EQ(backwards.front(), (Cell{3, 2}));
  EXPECT_EQ(backwards.back(), (Cell{0, 0}));
}

TEST(LineOfSight, SegmentClearAndFirstBlocked) {
  const PlanningGrid g = test::grid_from_art({
      "....",
      "..#.",
      "....",
  });
  EXPECT_TRUE(segment_clear(g, {0.5, 0.5}, {3.5, 0.5}, UnknownPolicy::Blocked));
  EXPECT_FALSE(segment_clear(g, {0.5, 1.5}, {3.5, 1.5}, UnknownPolicy::Blocked));
  EXPECT_NEAR(first_blocked_fraction(g, {0.5, 1.5}, {3.5, 1.5}, UnknownPolicy::Blocked), 0.5, 1e-9);
  // Clips the corner of the occupied cell (2,1): blocked.
  EXPECT_FALSE(segment_clear(g, {1.5, 0.5}, {2.5, 1.5}, UnknownPolicy::Blocked));
  EXPECT_FALSE(segment_clear(g, {0.5, 0.5}, {4.5, 0.5}, UnknownPolicy::Blocked));  // leaves map
}

TEST(PathReduction, DropsCollinearPoints) {
  const std::vector<Vec2> in{{0, 0}, {1, 0}, {2, 0}, {2, 0}, {3, 1}, {4, 2}, {4, 3}};
  const std::vector<Vec2> want{{0, 0}, {2, 0}, {4, 2}, {4, 3}};
  EXPECT_EQ(drop_collinear(in), want);
  // A reversal is not collinear continuation: the turn-back point stays.
  const std::vector<Vec2> back{{0, 0}, {2, 0}, {1, 0}};
  EXPECT_EQ(drop_collinear(back).size(), 3u);
}

TEST(PathReduction, ShortcutsOnlyWithLineOfSight) {
  const PlanningGrid g = test::grid_from_art({
      ".......",
      ".......",
      "...#...",
      "...#...",
      "...#...",
  });
  const std::vector<Vec2> around{{0.5, 0.5}, {1.5, 1.5}, {2.5, 3.5}, {3.5, 3.5},
                                 {4.5, 3.5}, {5.5, 1.5}, {6.5, 0.5}};
  const auto reduced = shortcut(g, around, UnknownPolicy::Blocked);
  EXPECT_LT(reduced.size(), around.size());
  EXPECT_LE(path_length(reduced), path_length(around));
  for (size_t i = 1; i < reduced.size(); ++i) {
    EXPECT_TRUE(segment_clear(g, reduced[i - 1], reduced[i], UnknownPolicy::Blocked));
  }
}

TEST(PathReduction, ReducedAstarPathsStayClear) {
  std::mt19937 rng(3);
  GridAstar astar;
  std::vector<Cell> cells;
  int checked = 0;
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<uint8_t> raw(40 * 40);
    for (auto& c : raw) c = (rng() % 100) < 25 ? kCellOccupied : kCellFree;
    PlanningGrid g;
    ASSERT_TRUE(g.reset({{-1.0, -1.0}, 0.05, 40, 40}, 1, 0, raw));
    const Cell s{static_cast<int32_t>(rng() % 40), static_cast<int32_t>(rng() % 40)};
    const Cell t{static_cast<int32_t>(rng() % 40), static_cast<int32_t>(rng() % 40)};
    if (astar.search(g, s, t, {}, cells) != PlanStatus::Ok) continue;
    const Vec2 start = g.centre(s);
    const Vec2 goal = g.centre(t);
    const auto path = reduce_cell_path(g, cells, start, goal, UnknownPolicy::Blocked);
    ASSERT_GE(path.size(), 2u);
    EXPECT_EQ(path.front(), start);
    EXPECT_EQ(path.back(), goal);
    EXPECT_LE(path_length(path), astar.last_cost() * 0.05 + 1e-9);
    EXPECT_LE(path.size(), cells.size() + 1);
    for (size_t i = 1; i < path.size(); ++i) {
      EXPECT_TRUE(segment_clear(g, path[i - 1], path[i], UnknownPolicy::Blocked)) << trial;
    }
    ++checked;
  }
  EXPECT_GT(checked, 30);
}

}  // namespace
}  // namespace slam::planner

#include "eval/map_metrics.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "simulator/core/builtin_worlds.hpp"

namespace slam::bench {
namespace {

constexpr double kRes = 0.05;

// An empty map covering [-1, w + 1] x [-1, h + 1] (cells) around a world of w x h metres.
MapImage empty_map(double w, double h) {
  MapImage m;
  m.resolution = kRes;
  m.origin_x = -1.0;
  m.origin_y = -1.0;
  m.width = static_cast<uint32_t>((w + 2.0) / kRes);
  m.height = static_cast<uint32_t>((h + 2.0) / kRes);
  m.cells.assign(static_cast<size_t>(m.width) * m.height, kMapUnknown);
  return m;
}

// Marks occupied every cell a wall touches, the walls shifted by `shift` cells in x.
void draw_walls(MapImage& m, std::span<const sim::Segment> walls, int shift) {
  for (uint32_t y = 0; y < m.height; ++y) {
    for (uint32_t x = 0; x < m.width; ++x) {
      const Vec2 lo{m.origin_x + (static_cast<int>(x) - shift) * kRes, m.origin_y + y * kRes};
      for (const sim::Segment& w : walls)
        if (segment_touches_box(w, lo, lo + Vec2{kRes, kRes})) m.cells[y * m.width + x] = kMapOccupied;
    }
  }
}

std::vector<sim::Segment> office_walls() {
  auto world = sim::builtin_world("office");
  EXPECT_TRUE(world) << world.message();
  return {world->walls().begin(), world->walls().end()};
}

TEST(WallScores, AMapDrawnFromTheWallsScoresPerfectly) {
  const auto walls = office_walls();
  MapImage map = empty_map(20.0, 15.0);
  draw_walls(map, walls, 0);
  const auto s = score_walls(map, walls);
  ASSERT_TRUE(s) << s.message();
  EXPECT_GT(s->occupied_cells, 1000u);
  EXPECT_DOUBLE_EQ(s->near_wall_share, 1.0);
  EXPECT_LE(s->mean_wall_distance_m, 0.5 * kRes * 1.5);
  EXPECT_DOUBLE_EQ(s->wall_found_share, 1.0);
}

TEST(WallScores, AMapShiftedByTwoCellsScoresWorse) {
  const auto walls = office_walls();
  MapImage exact = empty_map(20.0, 15.0), shifted = empty_map(20.0, 15.0);
  draw_walls(exact, walls, 0);
  draw_walls(shifted, walls, 2);
  const auto good = score_walls(exact, walls), bad = score_walls(shifted, walls);
  ASSERT_TRUE(good && bad);
  EXPECT_LT(bad->near_wall_share, good->near_wall_share - 0.2);
  EXPECT_GT(bad->mean_wall_distance_m, good->mean_wall_distance_m + 0.02);
  EXPECT_LT(bad->wall_found_share, good->wall_found_share - 0.2);
}

TEST(WallScores, RefusesRotatedMaps) {
  MapImage map = empty_map(1.0, 1.0);
  map.origin_yaw = 0.3;
  EXPECT_FALSE(score_walls(map, office_walls()));
}

std::vector<sim::Segment> room(double side) {
  return {{{0, 0}, {side, 0}}, {{side, 0}, {side, side}}, {{side, side}, {0, side}}, {{0, side}, {0, 0}}};
}

TEST(ReachableCoverage, HalfAnExploredRoomIsHalfCovered) {
  const auto walls = room(4.0);
  MapImage map = empty_map(4.0, 4.0);
  // Explored: everything left of x = 2 m, the middle of the room.
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x)
      map.cells[y * map.width + x] = map.origin_x + (x + 0.5) * kRes < 2.0 ? kMapFree : kMapUnknown;
  const std::vector<Vec2> starts = {{1.0, 1.0}};
  const auto c = reachable_coverage(map, walls, starts);
  ASSERT_TRUE(c) << c.message();
  // Inside a 4 m room at 5 cm: 80 x 80 cells; a wall on a cell edge blocks one or both cells
  // beside it (depending on rounding), leaving 78 to 79 cells per side.
  EXPECT_GE(c->reachable_cells, 78u * 78u);
  EXPECT_LE(c->reachable_cells, 79u * 79u);
  EXPECT_NEAR(c->share(), 0.5, 0.02);
}

TEST(ReachableCoverage, WallsStopTheFloodAndStartsOutsideCountNothing) {
  auto walls = room(4.0);
  walls.push_back({{2.0, 0.0}, {2.0, 4.0}});  // splits the room: only the start's half is reachable
  const MapImage map = empty_map(4.0, 4.0);
  const std::vector<Vec2> starts = {{1.0, 1.0}, {-0.5, -0.5}};
  const auto c = reachable_coverage(map, walls, starts);
  ASSERT_TRUE(c) << c.message();
  EXPECT_LT(c->reachable_cells, 78u * 40u);
  EXPECT_GT(c->reachable_cells, 78u * 37u);
  EXPECT_EQ(c->known_free, 0u);
}

TEST(SegmentTouchesBox, InsideCrossingAndMissing) {
  EXPECT_TRUE(segment_touches_box({{0.5, 0.5}, {0.6, 0.6}}, {0, 0}, {1, 1}));  // inside
  EXPECT_TRUE(segment_touches_box({{-1, 0.5}, {2, 0.5}}, {0, 0}, {1, 1}));     // through
  EXPECT_FALSE(segment_touches_box({{-1, 1.5}, {1, 3}}, {0, 0}, {1, 1}));      // passes above
  EXPECT_TRUE(segment_touches_box({{1, -1}, {1, 2}}, {0, 0}, {1, 1}));         // along an edge
}

}  // namespace
}  // namespace slam::bench

// BranchAndBoundSearch: finds a laser keyframe anywhere in a map at any heading, scores exactly as a
// brute-force search over the same lattice does, reports look-alike rooms as a runner-up scoring as
// well as the best, searches only the region asked, and refuses what it cannot search.
#include "pose_correction/branch_and_bound_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "synthetic_world.hpp"

namespace slam::correction {
namespace {

using testkit::ClassGrid;
using testkit::SparseSensor;
using testkit::SyntheticWorld;

constexpr double kResolution = 0.05;

// Six rooms with furniture that tells every one apart.
SyntheticWorld floor_plan() {
  SyntheticWorld w = testkit::six_rooms();
  w.wall({1.0, 1.0}, {1.0, 2.0});
  w.wall({2.5, 6.0}, {3.5, 7.0});
  w.wall({5.0, 5.0}, {6.0, 5.0});
  w.wall({6.5, 1.0}, {6.5, 2.8});
  w.wall({9.0, 6.8}, {10.5, 6.8});
  w.wall({10.0, 1.0}, {11.0, 1.5});
  return w;
}

// Three closed rooms, identical down to an L-shaped cupboard in the same corner of each.
SyntheticWorld identical_rooms() {
  SyntheticWorld w;
  for (double x0 : {0.0, 6.0, 12.0}) {
    w.room({x0, 0.0}, {x0 + 4.0, 4.0});
    w.wall({x0 + 0.5, 3.0}, {x0 + 1.5, 3.0});
    w.wall({x0 + 1.5, 3.0}, {x0 + 1.5, 3.5});
  }
  return w;
}

// One laser scan of 360 beams within 8 m, in the robot's frame.
std::vector<Vec2> laser_scan(const SyntheticWorld& world, const Pose& truth) {
  std::mt19937 rng(3);
  SparseSensor laser;
  laser.beams = 360;
  laser.max_range_m = 8.0;
  std::vector<Vec2> points;
  laser.observe(world, truth, truth, rng, points);
  return points;
}

struct Map {
  ClassGrid grid;
  GridView view() const { return {grid.geometry, grid.classes}; }
};

Map map_of(const SyntheticWorld& world, Vec2 lo, Vec2 hi) {
  return {ClassGrid::rasterise(world, testkit::centred_geometry(lo, hi))};
}

class GlobalPoses : public ::testing::TestWithParam<Pose> {};

TEST_P(GlobalPoses, FindsALaserKeyframeAnywhereAtAnyHeading) {
  const Pose truth = GetParam();
  const Map map = map_of(floor_plan(), {-0.5, -0.5}, {12.5, 8.5});
  BranchAndBoundSearch search;
  ASSERT_TRUE(search.set_map(map.view()));
  const auto m = search.search(laser_scan(floor_plan(), truth), SearchRegion{{6.0, 4.0, 0.0}, 7.0, 4.0});
  ASSERT_TRUE(m) << m.message();
  EXPECT_NEAR(m->pose.x, truth.x, 1.5 * kResolution);
  EXPECT_NEAR(m->pose.y, truth.y, 1.5 * kResolution);
  EXPECT_NEAR(wrap_angle(m->pose.theta - truth.theta), 0.0, 0.02);
  EXPECT_GT(m->score, 0.8);
  EXPECT_LT(m->ambiguity(), 0.9);
}

INSTANTIATE_TEST_SUITE_P(Floor, GlobalPoses,
                         ::testing::Values(Pose{2.0, 6.0, 2.5}, Pose{6.3, 2.2, -2.0}, Pose{10.7, 3.1, 0.1},
                                           Pose{5.5, 5.9, -3.0}));

TEST(BranchAndBoundSearch, ScoresExactlyAsABruteForceSearchOverTheSameLattice) {
  const SyntheticWorld world = floor_plan();
  const Map map = map_of(world, {-0.5, -0.5}, {12.5, 8.5});
  const Pose truth{3.0, 2.0, 0.7};
  const std::vector<Vec2> points = laser_scan(world, truth);
  const SearchRegion region{{3.3, 1.8, 0.7}, 0.6, 0.0};  // one heading: the brute force's
  BranchAndBoundSearch search;
  ASSERT_TRUE(search.set_map(map.view()));
  const auto m = search.search(points, region);
  ASSERT_TRUE(m) << m.message();

  LikelihoodField field(0.05);
  const GridGeometry& g = map.grid.geometry;
  ASSERT_TRUE(field.build(map.view(), CellBox{-64, -64, g.width + 128, g.height + 128}, size_t{1} << 24));
  const int32_t reach = static_cast<int32_t>(std::ceil(region.linear_m / kResolution - 1e-9));
  float best = -1.0f;
  Vec2 best_at;
  for (int32_t ty = -reach; ty <= reach; ++ty) {
    for (int32_t tx = -reach; tx <= reach; ++tx) {
      const Pose p{region.centre.x + tx * kResolution, region.centre.y + ty * kResolution,
                   region.centre.theta};
      float sum = 0.0f;
      for (const Vec2& q : points) {
        const Vec2 c = g.to_grid(region.centre.transform(q));
        sum +=
            field.at(static_cast<int32_t>(std::floor(c.x)) + tx, static_cast<int32_t>(std::floor(c.y)) + ty);
      }
      if (sum > best) {
        best = sum;
        best_at = p.position();
      }
    }
  }
  EXPECT_FLOAT_EQ(static_cast<float>(m->score * static_cast<double>(points.size())), best);
  EXPECT_NEAR(m->pose.x, best_at.x, 1e-9);
  EXPECT_NEAR(m->pose.y, best_at.y, 1e-9);
  EXPECT_NEAR(m->pose.x, truth.x, kResolution);
  EXPECT_NEAR(m->pose.y, truth.y, kResolution);
}

TEST(BranchAndBoundSearch, ReportsIdenticalRoomsAsARunnerUpAsGoodAsTheBest) {
  const SyntheticWorld world = identical_rooms();
  const Map map = map_of(world, {-0.5, -0.5}, {16.5, 4.5});
  BranchAndBoundSearch search;
  ASSERT_TRUE(search.set_map(map.view()));
  const auto m = search.search(laser_scan(world, {8.0, 1.5, 0.4}), SearchRegion{{8.0, 2.0, 0.0}, 8.5, 4.0});
  ASSERT_TRUE(m) << m.message();
  EXPECT_GT(m->score, 0.8);
  EXPECT_GT(m->ambiguity(), 0.95);
}

TEST(BranchAndBoundSearch, SearchesOnlyTheRegionAskedFor) {
  const SyntheticWorld world = identical_rooms();
  const Map map = map_of(world, {-0.5, -0.5}, {16.5, 4.5});
  BranchAndBoundSearch search;
  ASSERT_TRUE(search.set_map(map.view()));
  // Around the right room only, the look-alikes are out of reach: the match is the truth, unique.
  const Pose truth{14.0, 1.5, 0.4};
  const auto m = search.search(laser_scan(world, truth), SearchRegion{{13.8, 1.7, 0.5}, 0.5, 0.3});
  ASSERT_TRUE(m) << m.message();
  EXPECT_NEAR(m->pose.x, truth.x, 1.5 * kResolution);
  EXPECT_NEAR(m->pose.y, truth.y, 1.5 * kResolution);
  EXPECT_NEAR(wrap_angle(m->pose.theta - truth.theta), 0.0, 0.02);
  EXPECT_LT(m->ambiguity(), 0.9);
}

TEST(BranchAndBoundSearch, RefusesWhatItCannotSearch) {
  const SyntheticWorld world = identical_rooms();
  const Map map = map_of(world, {-0.5, -0.5}, {16.5, 4.5});
  const std::vector<Vec2> points = laser_scan(world, {2.0, 2.0, 0.0});
  BranchAndBoundSearch search;
  EXPECT_FALSE(search.search(points, SearchRegion{}));  // no map yet
  EXPECT_FALSE(search.set_map(GridView{}));
  ASSERT_TRUE(search.set_map(map.view()));
  EXPECT_FALSE(search.search(std::span(points).first(5), SearchRegion{{2.0, 2.0, 0.0}, 1.0, 0.1}));
  EXPECT_FALSE(
      search.search(points, SearchRegion{{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}, 1.0, 0.1}));
  EXPECT_FALSE(search.search(points, SearchRegion{{1e7, 0.0, 0.0}, 1.0, 0.1}));
  // Free space everywhere in reach: nothing scores.
  const std::vector<Vec2> far_points(50, Vec2{0.1, 0.1});
  EXPECT_FALSE(search.search(far_points, SearchRegion{{2.0, 2.0, 0.0}, 0.2, 0.1}));
  BranchAndBoundOptions tiny;
  tiny.max_map_cells = 1000;
  BranchAndBoundSearch refusing(tiny);
  EXPECT_FALSE(refusing.set_map(map.view()));
}

}  // namespace
}  // namespace slam::correction

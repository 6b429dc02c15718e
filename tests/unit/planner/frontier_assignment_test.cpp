// Frontier assignment (unique, utility-driven, lazy costs), blacklist and progress watch.
#include "planner/core/frontier_assignment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "grid_builder.hpp"

namespace slam::planner {
namespace {

PathCost straight() {
  return [](Vec2 a, Vec2 b) -> std::optional<double> { return distance(a, b); };
}

TEST(FrontierAssignment, NoTwoRobotsShareACluster) {
  const PlanningGrid g = test::uniform_grid(100, 100, kCellFree);
  std::vector<FrontierCluster> clusters;
  for (int i = 0; i < 5; ++i) clusters.push_back({10, {}, Cell{10 + 20 * i, 50}});
  std::vector<ExploringRobot> robots;
  for (uint32_t r = 0; r < 8; ++r) robots.push_back({r, Vec2{50.0, 10.0 + r}});
  const std::vector<uint8_t> all(clusters.size(), 1);
  const auto out = assign_frontiers(robots, clusters, all, g, 1.0, straight());
  ASSERT_EQ(out.size(), 5u);  // more robots than clusters: five get one
  std::set<size_t> used_clusters;
  std::set<uint32_t> used_robots;
  for (const auto& a : out) {
    EXPECT_TRUE(used_clusters.insert(a.cluster).second);
    EXPECT_TRUE(used_robots.insert(a.robot).second);
  }
}

TEST(FrontierAssignment, PrefersNearAndLargeFrontiers) {
  const PlanningGrid g = test::uniform_grid(100, 100, kCellFree);
  const std::vector<FrontierCluster> clusters{
      {5, {}, Cell{10, 0}},    // near, small
      {5, {}, Cell{90, 0}},    // far, small
      {200, {}, Cell{60, 0}},  // further but huge
  };
  const std::vector<ExploringRobot> one{{7, Vec2{0.5, 0.5}}};
  const std::vector<uint8_t> all(3, 1);
  auto out = assign_frontiers(one, clusters, all, g, 0.0, straight());
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].cluster, 0u);  // gain ignored: nearest
  EXPECT_EQ(out[0].robot, 7u);
  out = assign_frontiers(one, clusters, all, g, 1.0, straight());
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].cluster, 2u);  // 200 m of frontier outweighs 50 m more travel
  const std::vector<uint8_t> not_big{1, 1, 0};
  out = assign_frontiers(one, clusters, not_big, g, 1.0, straight());
  EXPECT_EQ(out[0].cluster, 0u);
}

TEST(FrontierAssignment, SkipsUnreachableAndComputesFewCosts) {
  const PlanningGrid g = test::uniform_grid(100, 100, kCellFree);
  std::vector<FrontierCluster> clusters;
  for (int i = 0; i < 50; ++i) clusters.push_back({5, {}, Cell{2 * i, 99}});
  const std::vector<ExploringRobot> one{{0, Vec2{0.5, 98.5}}};
  int calls = 0;
  const PathCost cost = [&](Vec2 a, Vec2 b) -> std::optional<double> {
    ++calls;
    if (b.x < 1.0) return std::nullopt;  // the nearest one is walled off
    return distance(a, b);
  };
  const std::vector<uint8_t> all(clusters.size(), 1);
  const auto out = assign_frontiers(one, clusters, all, g, 0.0, cost);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].cluster, 1u);
  EXPECT_LE(calls, 3);
}

TEST(FrontierBlacklist, MatchesWithinRadius) {
  FrontierBlacklist b;
  b.add({1.0, 1.0}, 0, 100, 0.5);
  EXPECT_TRUE(b.contains({1.3, 1.0}, 0.5, 0));
  EXPECT_FALSE(b.contains({2.0, 1.0}, 0.5, 0));
}

TEST(FrontierBlacklist, AFirstFailureRestsThePlaceASecondGivesItUp) {
  FrontierBlacklist b;
  b.add({1.0, 1.0}, 0, 100, 0.5);
  EXPECT_TRUE(b.contains({1.0, 1.0}, 0.5, 99));
  EXPECT_FALSE(b.contains({1.0, 1.0}, 0.5, 100));  // offered again
  b.add({1.2, 1.0}, 200, 100, 0.5);                // failed again nearby: for good
  EXPECT_TRUE(b.contains({1.2, 1.0}, 0.5, 1'000'000));
  EXPECT_EQ(b.size(), 2u);
  b.clear();
  EXPECT_FALSE(b.contains({1.2, 1.0}, 0.5, 300));
}

TEST(ProgressWatch, StallsWithoutProgress) {
  ExplorerConfig c;
  c.progress_timeout_s = 10.0;
  c.progress_min_m = 0.5;
  ProgressWatch w;
  w.start({10, 0}, 0);
  EXPECT_FALSE(w.stalled(12.0, 1'000'000'000, c));   // the first measure is progress
  EXPECT_FALSE(w.stalled(11.0, 5'000'000'000, c));   // progress at t=5 s
  EXPECT_FALSE(w.stalled(10.8, 14'000'000'000, c));  // too little, but < 10 s since t=5
  EXPECT_TRUE(w.stalled(10.8, 15'500'000'000, c));
}

TEST(ProgressWatch, ProgressIsTheWayLeftNotTheStraightLine) {
  // A path winding away from its target still makes progress while it gets shorter.
  ExplorerConfig c;
  c.progress_timeout_s = 1.0;
  ProgressWatch w;
  w.start({1, 0}, 0);
  for (int64_t t = 0; t <= 20; ++t) {
    EXPECT_FALSE(w.stalled(20.0 - static_cast<double>(t), t * 900'000'000, c)) << t;
  }
}

TEST(ExplorerConfig, Validates) {
  ExplorerConfig c;
  EXPECT_TRUE(validate(c));
  c.min_cluster_cells = 0;
  EXPECT_FALSE(validate(c));
  c = {};
  c.progress_timeout_s = -1;
  EXPECT_FALSE(validate(c));
  c = {};
  c.blacklist_rest_s = -1;
  EXPECT_FALSE(validate(c));
  c = {};
  c.completion_grace_s = std::nan("");
  EXPECT_FALSE(validate(c));
  c = {};
  c.retry_period_s = 0;
  EXPECT_FALSE(validate(c));
}

}  // namespace
}  // namespace slam::planner

#include "eval/waypoint_arrivals.hpp"

#include <gtest/gtest.h>

namespace slam::bench {
namespace {

const std::vector<Vec2> kPath = {{1.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}};

TEST(WaypointArrivals, CountsEveryWaypointTheCurrentIndexMovesPast) {
  WaypointArrivals arrivals(0.2);
  EXPECT_TRUE(arrivals.update("r", {7, kPath, 0}, Vec2{0.0, 0.0}).empty());  // first sample: nothing before
  EXPECT_EQ(arrivals.update("r", {7, kPath, 1}, Vec2{1.0, 0.0}), (std::vector<Vec2>{kPath[0]}));
  EXPECT_EQ(arrivals.update("r", {7, kPath, 3}, Vec2{2.0, 1.0}), (std::vector<Vec2>{kPath[1], kPath[2]}));
  EXPECT_TRUE(arrivals.update("r", {7, kPath, 3}, Vec2{2.0, 1.0}).empty());  // nothing new
}

TEST(WaypointArrivals, AClearedPathCountsWhenTheRobotIsAtItsEnd) {
  WaypointArrivals arrivals(0.2);
  arrivals.update("r", {7, kPath, 2}, Vec2{2.0, 0.5});
  EXPECT_EQ(arrivals.update("r", {7, {}, 0}, Vec2{2.05, 0.95}), (std::vector<Vec2>{kPath[2]}));
}

TEST(WaypointArrivals, AReplacedOrDroppedPathCountsNothing) {
  WaypointArrivals arrivals(0.2);
  arrivals.update("r", {7, kPath, 2}, Vec2{2.0, 0.5});
  EXPECT_TRUE(arrivals.update("r", {7, {{5.0, 5.0}}, 0}, Vec2{2.0, 0.6}).empty());  // re-planned midway
  arrivals.update("s", {7, kPath, 0}, Vec2{0.0, 0.0});
  EXPECT_TRUE(arrivals.update("s", {8, {}, 0}, Vec2{0.5, 0.0}).empty());  // new goal before arriving
}

TEST(WaypointArrivals, RobotsAreTrackedApart) {
  WaypointArrivals arrivals(0.2);
  arrivals.update("a", {1, kPath, 0}, std::nullopt);
  EXPECT_TRUE(arrivals.update("b", {1, kPath, 1}, std::nullopt).empty());
  EXPECT_EQ(arrivals.update("a", {1, kPath, 1}, std::nullopt).size(), 1u);
}

}  // namespace
}  // namespace slam::bench

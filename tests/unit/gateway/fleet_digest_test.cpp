// The gateway's fleet digests: every known robot with its map-frame pose and presence, and each
// robot's latest hits since the previous points digest, in the map frame.
#include "gateway/core/fleet_digest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <string>
#include <vector>

namespace slam::gateway {
namespace {

// map <- odom: a quarter turn left about the map point (1, 2): odometry (a, b) is map (1 - b, 2 + a).
const Pose kQuarterTurn{1.0, 2.0, std::numbers::pi / 2};

protocol::DecodedObservation observation_at(double x, double y, double theta) {
  protocol::DecodedObservation o;
  o.x = x;
  o.y = y;
  o.theta = theta;
  o.has_pose = true;
  o.has_heading = true;
  return o;
}

const DigestRobotEntry* find(std::span<const DigestRobotEntry> robots, const std::string& id) {
  for (const DigestRobotEntry& r : robots)
    if (r.id == id) return &r;
  return nullptr;
}

const DigestPointsEntry* find(std::span<const DigestPointsEntry> points, const std::string& id) {
  for (const DigestPointsEntry& p : points)
    if (p.id == id) return &p;
  return nullptr;
}

TEST(FleetDigestBuilder, ListsEveryRobotWithItsPoseInTheMapFrame) {
  RobotRegistry registry;
  auto a = observation_at(1.0, 0.0, 0.0);
  auto b = observation_at(0.0, 0.0, 0.5);
  ASSERT_EQ(registry.accept_observation("a", Protocol::V2, a, {100, 1}).kind, AcceptResult::Kind::Accepted);
  ASSERT_EQ(registry.accept_observation("b", Protocol::V2, b, {200, 2}).kind, AcceptResult::Kind::Accepted);
  CorrectionTable corrections;
  ASSERT_TRUE(corrections.update("a", {kQuarterTurn, 1}));

  FleetDigestBuilder digest(8);
  digest.collect(registry);
  digest.place_robots(corrections);

  ASSERT_EQ(digest.robots().size(), 2u);
  const DigestRobotEntry* ra = find(digest.robots(), "a");
  ASSERT_NE(ra, nullptr);
  EXPECT_NEAR(ra->pose.x, 1.0, 1e-12);
  EXPECT_NEAR(ra->pose.y, 3.0, 1e-12);
  EXPECT_NEAR(ra->pose.theta, std::numbers::pi / 2, 1e-12);
  EXPECT_TRUE(ra->online);
  EXPECT_TRUE(ra->has_heading);
  EXPECT_EQ(ra->last_seen_ns, 100);
  const DigestRobotEntry* rb = find(digest.robots(), "b");
  ASSERT_NE(rb, nullptr);  // uncorrected: its odometry frame is the map frame
  EXPECT_EQ(rb->pose, (Pose{0.0, 0.0, 0.5}));
  EXPECT_EQ(rb->last_seen_ns, 200);
}

TEST(FleetDigestBuilder, ShowsOfflineRobotsAndDropsForgottenOnes) {
  RobotRegistry registry(RegistryConfig{1'000, 10});
  auto a = observation_at(0, 0, 0);
  auto b = observation_at(0, 0, 0);
  registry.accept_observation("a", Protocol::V1, a, {0, 0});
  registry.accept_observation("b", Protocol::V1, b, {0, 5'000});
  registry.expire({0, 3'000});  // a silent past offline_after, b heard since
  FleetDigestBuilder digest(8);
  digest.collect(registry);
  ASSERT_EQ(digest.robots().size(), 2u);
  EXPECT_FALSE(find(digest.robots(), "a")->online);
  EXPECT_TRUE(find(digest.robots(), "b")->online);

  registry.forget("a");
  digest.collect(registry);
  ASSERT_EQ(digest.robots().size(), 1u);
  EXPECT_EQ(digest.robots()[0].id, "b");
}

TEST(FleetDigestBuilder, PointsAreTheLatestHitsSinceTheLastTakeInTheMapFrame) {
  FleetDigestBuilder digest(3);
  const std::vector<protocol::Point> first{{1, 0}, {2, 0}};
  const std::vector<protocol::Point> second{{3, 0}, {4, 0}};
  digest.add_hits("a", first, 10);
  digest.add_hits("a", second, 20);
  digest.add_hits("b", first, 15);
  CorrectionTable corrections;
  ASSERT_TRUE(corrections.update("a", {kQuarterTurn, 1}));

  digest.take_points();
  digest.place_points(corrections);
  ASSERT_EQ(digest.points().size(), 2u);
  const DigestPointsEntry* pa = find(digest.points(), "a");
  ASSERT_NE(pa, nullptr);
  EXPECT_EQ(pa->stamp_ns, 20);
  // The ring keeps the last three of (1,0) (2,0) (3,0) (4,0): odometry x = 2, 3, 4 -> map (1, 2 + x).
  std::vector<double> map_y;
  for (const Vec2& p : pa->points) {
    EXPECT_NEAR(p.x, 1.0, 1e-12);
    map_y.push_back(p.y);
  }
  std::sort(map_y.begin(), map_y.end());
  ASSERT_EQ(map_y.size(), 3u);
  EXPECT_NEAR(map_y[0], 4.0, 1e-12);
  EXPECT_NEAR(map_y[1], 5.0, 1e-12);
  EXPECT_NEAR(map_y[2], 6.0, 1e-12);
  ASSERT_NE(find(digest.points(), "b"), nullptr);
  EXPECT_EQ(find(digest.points(), "b")->points.size(), 2u);

  // Nothing new since: the next take is empty, and a robot heard again comes back alone.
  digest.take_points();
  EXPECT_TRUE(digest.points().empty());
  digest.add_hits("b", second, 30);
  digest.take_points();
  ASSERT_EQ(digest.points().size(), 1u);
  EXPECT_EQ(digest.points()[0].id, "b");
  EXPECT_EQ(digest.points()[0].points.size(), 2u);
}

TEST(FleetDigestBuilder, ForgottenRobotsLoseTheirPendingPoints) {
  FleetDigestBuilder digest(4);
  const std::vector<protocol::Point> hits{{1, 1}};
  digest.add_hits("a", hits, 1);
  digest.forget("a");
  digest.take_points();
  EXPECT_TRUE(digest.points().empty());
}

}  // namespace
}  // namespace slam::gateway

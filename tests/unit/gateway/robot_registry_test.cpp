// RobotRegistry: first sight, sequence numbers, presence transitions, counters, bounds.
#include "gateway/core/robot_registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace slam::gateway {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

Instant at(int64_t s) {
  return {1'700'000'000 * kSecond + s * kSecond, s * kSecond};
}

protocol::DecodedObservation pose_at(double x, double y, size_t hits = 0) {
  protocol::DecodedObservation o;
  o.has_pose = true;
  o.x = x;
  o.y = y;
  for (size_t i = 0; i < hits; ++i) o.hits.push_back({x + 1.0, y});
  return o;
}

std::vector<std::string> changed_ids(RobotRegistry& registry) {
  std::vector<std::string> out;
  registry.take_changed([&](const RobotRecord& r) { out.push_back(r.id); });
  return out;
}

TEST(RobotRegistry, FirstValidMessageCreatesTheRobotOnlineWithSequenceOne) {
  RobotRegistry registry;
  auto obs = pose_at(1.0, -2.5, 3);
  const AcceptResult r = registry.accept_observation("r1", Protocol::V1, obs, at(10));
  EXPECT_EQ(r.kind, AcceptResult::Kind::Accepted);
  EXPECT_EQ(r.seq, 1u);
  EXPECT_TRUE(r.first_seen);
  EXPECT_FALSE(r.came_online);
  const RobotRecord* rec = registry.find("r1");
  ASSERT_NE(rec, nullptr);
  EXPECT_EQ(rec->presence, Presence::Online);
  EXPECT_EQ(rec->protocol, Protocol::V1);
  EXPECT_EQ(rec->first_seen_ns, at(10).wall_ns);
  EXPECT_EQ(rec->last_seen_ns, at(10).wall_ns);
  EXPECT_EQ(rec->messages, 1u);
  EXPECT_EQ(rec->points, 3u);
  EXPECT_DOUBLE_EQ(rec->x, 1.0);
  EXPECT_DOUBLE_EQ(rec->y, -2.5);
  EXPECT_EQ(registry.online(), 1u);
}

TEST(RobotRegistry, SequenceCountsPerRobot) {
  RobotRegistry registry;
  auto a = pose_at(0, 0);
  EXPECT_EQ(registry.accept_observation("a", Protocol::V1, a, at(1)).seq, 1u);
  EXPECT_EQ(registry.accept_observation("a", Protocol::V1, a, at(2)).seq, 2u);
  EXPECT_EQ(registry.accept_observation("b", Protocol::V2, a, at(2)).seq, 1u);
  EXPECT_EQ(registry.accept_observation("a", Protocol::V1, a, at(3)).seq, 3u);
  EXPECT_EQ(registry.find("a")->messages, 3u);
  EXPECT_EQ(registry.find("a")->first_seen_ns, at(1).wall_ns);
  EXPECT_EQ(registry.find("a")->last_seen_ns, at(3).wall_ns);
}

TEST(RobotRegistry, ProtocolFollowsTheLatestValidMessage) {
  RobotRegistry registry;
  EXPECT_FALSE(registry.protocol_of("r").has_value());
  auto o = pose_at(0, 0);
  registry.accept_observation("r", Protocol::V1, o, at(1));
  EXPECT_EQ(registry.protocol_of("r"), Protocol::V1);
  registry.accept_observation("r", Protocol::V2, o, at(2));
  EXPECT_EQ(registry.protocol_of("r"), Protocol::V2);
}

TEST(RobotRegistry, PointsWithoutPoseUseTheLastPoseOrAreRefused) {
  RobotRegistry registry;
  protocol::DecodedObservation points;
  points.hits.push_back({3.0, 4.0});
  const AcceptResult refused = registry.accept_observation("r", Protocol::V2, points, at(1));
  EXPECT_EQ(refused.kind, AcceptResult::Kind::NoPose);
  EXPECT_EQ(registry.find("r"), nullptr) << "a refused message must not create the robot";

  protocol::DecodedObservation pose = pose_at(1.0, 2.0);
  pose.has_heading = true;
  pose.theta = 0.5;
  registry.accept_observation("r", Protocol::V2, pose, at(2));
  const AcceptResult ok = registry.accept_observation("r", Protocol::V2, points, at(3));
  EXPECT_EQ(ok.kind, AcceptResult::Kind::Accepted);
  EXPECT_EQ(ok.seq, 2u);
  EXPECT_TRUE(points.has_pose);
  EXPECT_DOUBLE_EQ(points.x, 1.0);
  EXPECT_DOUBLE_EQ(points.y, 2.0);
  EXPECT_TRUE(points.has_heading);
  EXPECT_DOUBLE_EQ(points.theta, 0.5);
  EXPECT_EQ(registry.find("r")->points, 1u);
}

TEST(RobotRegistry, SilenceTurnsRobotsOfflineAndAMessageBringsThemBack) {
  RobotRegistry registry(RegistryConfig{5 * kSecond, 100});
  auto o = pose_at(0, 0);
  registry.accept_observation("quiet", Protocol::V1, o, at(0));
  registry.accept_observation("busy", Protocol::V1, o, at(0));
  registry.accept_observation("busy", Protocol::V1, o, at(4));
  changed_ids(registry);

  std::vector<std::string> offline;
  registry.expire(at(4), [&](const RobotRecord& r) { offline.push_back(r.id); });
  EXPECT_TRUE(offline.empty());
  registry.expire(at(5), [&](const RobotRecord& r) { offline.push_back(r.id); });
  EXPECT_EQ(offline, std::vector<std::string>{"quiet"});
  EXPECT_EQ(registry.find("quiet")->presence, Presence::Offline);
  EXPECT_EQ(registry.online(), 1u);
  EXPECT_EQ(changed_ids(registry), std::vector<std::string>{"quiet"});
  registry.expire(at(6), [&](const RobotRecord& r) { offline.push_back(r.id); });
  EXPECT_EQ(offline.size(), 1u) << "an offline robot is reported once";

  const AcceptResult back = registry.accept_observation("quiet", Protocol::V1, o, at(7));
  EXPECT_TRUE(back.came_online);
  EXPECT_FALSE(back.first_seen);
  EXPECT_EQ(registry.find("quiet")->presence, Presence::Online);
  EXPECT_EQ(registry.online(), 2u);
}

TEST(RobotRegistry, LastWillTurnsTheRobotOfflineAtOnceAndSetsBatteryAndState) {
  RobotRegistry registry;
  protocol::DecodedStatus status;
  status.battery = 0.82f;
  status.state = "exploring";
  const AcceptResult first = registry.accept_status("r", status, at(1));
  EXPECT_TRUE(first.first_seen);
  EXPECT_EQ(first.seq, 0u);
  EXPECT_EQ(registry.find("r")->protocol, Protocol::V2);
  EXPECT_FLOAT_EQ(registry.find("r")->battery, 0.82f);
  EXPECT_EQ(registry.find("r")->status, "exploring");

  protocol::DecodedStatus will;
  will.state = "offline";
  will.offline = true;
  const AcceptResult gone = registry.accept_status("r", will, at(2));
  EXPECT_TRUE(gone.went_offline);
  EXPECT_FALSE(gone.came_online);
  EXPECT_EQ(registry.find("r")->presence, Presence::Offline);
  EXPECT_EQ(registry.find("r")->status, "offline");
  EXPECT_EQ(registry.online(), 0u);

  const AcceptResult again = registry.accept_status("r", will, at(3));
  EXPECT_FALSE(again.went_offline) << "already offline";
  EXPECT_EQ(registry.online(), 0u);
}

TEST(RobotRegistry, RejectionsCountOnlyForKnownRobots) {
  RobotRegistry registry;
  registry.count_rejected("stranger");
  EXPECT_EQ(registry.size(), 0u);
  auto o = pose_at(0, 0);
  registry.accept_observation("r", Protocol::V1, o, at(1));
  changed_ids(registry);
  registry.count_rejected("r");
  registry.count_rejected("r");
  EXPECT_EQ(registry.find("r")->rejected, 2u);
  EXPECT_EQ(registry.find("r")->messages, 1u);
  EXPECT_EQ(changed_ids(registry), std::vector<std::string>{"r"});
}

TEST(RobotRegistry, ChangedRobotsAreReportedOnce) {
  RobotRegistry registry;
  auto o = pose_at(0, 0);
  registry.accept_observation("a", Protocol::V1, o, at(1));
  registry.accept_observation("b", Protocol::V1, o, at(1));
  auto ids = changed_ids(registry);
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(changed_ids(registry).empty());
  registry.accept_observation("b", Protocol::V1, o, at(2));
  EXPECT_EQ(changed_ids(registry), std::vector<std::string>{"b"});
}

TEST(RobotRegistry, MarkingAKnownRobotChangedReportsItAgain) {
  RobotRegistry registry;
  auto o = pose_at(0, 0);
  registry.accept_observation("a", Protocol::V1, o, at(1));
  EXPECT_EQ(changed_ids(registry), std::vector<std::string>{"a"});
  registry.mark_changed("a");
  EXPECT_EQ(changed_ids(registry), std::vector<std::string>{"a"});
  registry.mark_changed("unknown");
  EXPECT_TRUE(changed_ids(registry).empty());
  EXPECT_EQ(registry.size(), 1u);
}

// A presence change goes out at once, alone: the robots that only moved wait for the state period.
TEST(RobotRegistry, OnlyPresenceChangesAreUrgent) {
  RobotRegistry registry(RegistryConfig{5 * kSecond, 10});
  auto o = pose_at(0, 0);
  registry.accept_observation("a", Protocol::V1, o, at(1));
  registry.accept_observation("b", Protocol::V1, o, at(1));
  EXPECT_EQ(changed_ids(registry).size(), 2u);
  registry.accept_observation("a", Protocol::V1, o, at(2));  // moved
  registry.accept_observation("c", Protocol::V1, o, at(2));  // first seen
  std::vector<std::string> urgent;
  registry.take_changed([&](const RobotRecord& r) { urgent.push_back(r.id); }, true);
  EXPECT_EQ(urgent, std::vector<std::string>{"c"});
  EXPECT_EQ(changed_ids(registry), std::vector<std::string>{"a"});
  registry.accept_observation("a", Protocol::V1, o, at(3));
  registry.expire(at(6));  // b silent for 5 s; c for 4 s, a for 3 s
  urgent.clear();
  registry.take_changed([&](const RobotRecord& r) { urgent.push_back(r.id); }, true);
  EXPECT_EQ(urgent, std::vector<std::string>{"b"});
}

TEST(RobotRegistry, NewRobotsBeyondTheLimitAreRefusedKnownOnesContinue) {
  RobotRegistry registry(RegistryConfig{5 * kSecond, 2});
  auto o = pose_at(0, 0);
  registry.accept_observation("a", Protocol::V1, o, at(1));
  registry.accept_observation("b", Protocol::V1, o, at(1));
  EXPECT_EQ(registry.accept_observation("c", Protocol::V1, o, at(1)).kind, AcceptResult::Kind::RegistryFull);
  protocol::DecodedStatus s;
  s.state = "idle";
  EXPECT_EQ(registry.accept_status("d", s, at(1)).kind, AcceptResult::Kind::RegistryFull);
  EXPECT_EQ(registry.size(), 2u);
  EXPECT_EQ(registry.accept_observation("a", Protocol::V1, o, at(2)).kind, AcceptResult::Kind::Accepted);
}

TEST(RobotRegistry, ForgottenRobotIsGoneAndComesBackNewWithSequenceOne) {
  RobotRegistry registry;
  auto a = pose_at(1, 1);
  registry.accept_observation("a", Protocol::V1, a, at(1));
  registry.accept_observation("a", Protocol::V1, a, at(2));
  changed_ids(registry);
  EXPECT_TRUE(registry.forget("a"));
  EXPECT_EQ(registry.find("a"), nullptr);
  EXPECT_EQ(registry.online(), 0u);
  EXPECT_TRUE(changed_ids(registry).empty());
  EXPECT_FALSE(registry.forget("a"));
  const AcceptResult again = registry.accept_observation("a", Protocol::V1, a, at(3));
  EXPECT_TRUE(again.first_seen);
  EXPECT_EQ(again.seq, 1u);
  EXPECT_EQ(registry.online(), 1u);
}

TEST(RobotRegistry, ForgettingAnOfflineRobotKeepsTheOnlineCount) {
  RobotRegistry registry({kSecond, 10});
  auto a = pose_at(1, 1);
  registry.accept_observation("a", Protocol::V1, a, at(1));
  registry.accept_observation("b", Protocol::V1, a, at(5));
  registry.expire(at(3));
  ASSERT_EQ(registry.online(), 1u);
  EXPECT_TRUE(registry.forget("a"));
  EXPECT_EQ(registry.online(), 1u);
}

}  // namespace
}  // namespace slam::gateway

// The frames contract through a real slam-gateway and mosquitto: a PoseCorrection on DDS moves what
// the gateway publishes for a robot into the map frame (RobotState) with the raw pose beside it
// (RobotOdometry), and map-frame waypoints leave on MQTT in the robot's odometry frame (exact v1
// bytes, v2 JSON); the fleet digests carry map-frame poses and points.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

constexpr double kPi = std::numbers::pi;

bool near(double a, double b) {
  return std::abs(a - b) < 1e-9;
}

Point2 point(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

class GatewayFramesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto p = dds::Participant::create(domain.id(), "gateway-frames-test");
    ASSERT_TRUE(p) << p.message();
    participant = std::move(*p);
    state_reader = make_inbox_reader(*participant, dds::kRobotState, states);
    odometry_reader = make_inbox_reader(*participant, dds::kRobotOdometry, odometry);
    subscriptions_reader = make_inbox_reader(*participant, dds::kMqttSubscriptions, subscriptions);
    correction_writer = make_test_writer(*participant, dds::kPoseCorrection);
    waypoint_writer = make_test_writer(*participant, dds::kWaypointCommand);

    group.start("gateway", {bin_path("slam-gateway"), "--domain", std::to_string(domain.id()), "--broker",
                            "tcp://127.0.0.1:" + std::to_string(port), "--log-level", "debug",
                            "--no-share"});  // a lone gateway: waypoints go out from its start
    ASSERT_TRUE(subscriptions.wait_for([](const MqttSubscriptions& s) { return s.connected(); }, 20s))
        << group.log("gateway");
    ASSERT_TRUE(wait_until(
        [&] { return correction_writer->matched_readers() > 0 && waypoint_writer->matched_readers() > 0; },
        10s));
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "gateway log:\n" << group.log("gateway") << "\n";
  }

  // The mapper's part: robot `id`'s odometry frame sits at (x, y, theta) in the map.
  void correct(const std::string& id, double x, double y, double theta, uint64_t version) {
    PoseCorrection c;
    c.robot_id(id);
    c.version(version);
    c.map_from_odom().x(x);
    c.map_from_odom().y(y);
    c.map_from_odom().theta(theta);
    c.source(CORRECTION_MATCH);
    ASSERT_TRUE(correction_writer->write(c));
  }
  // The planner's part: a waypoint and the rest of the path, in the map frame.
  void send_waypoint(const std::string& id, uint64_t seq, Point2 waypoint, std::vector<Point2> rest = {}) {
    WaypointCommand c;
    c.robot_id(id);
    c.seq(seq);
    c.waypoint(waypoint);
    c.remaining(std::move(rest));
    ASSERT_TRUE(waypoint_writer->write(c));
  }
  std::optional<RobotState> state_at(const std::string& id, double x, double y) {
    return states.wait_for(
        [&](const RobotState& s) {
          return s.robot_id() == id && near(s.pose().x(), x) && near(s.pose().y(), y);
        },
        10s);
  }
  std::optional<RobotOdometry> odometry_with(const std::string& id, uint64_t version) {
    return odometry.wait_for(
        [&](const RobotOdometry& o) { return o.robot_id() == id && o.correction_version() == version; }, 10s);
  }

  DomainLease domain;
  ProcessGroup group;
  int port = group.start_mosquitto();
  Inbox<RobotState> states;
  Inbox<RobotOdometry> odometry;
  Inbox<MqttSubscriptions> subscriptions;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Reader<RobotState>> state_reader;
  std::unique_ptr<dds::Reader<RobotOdometry>> odometry_reader;
  std::unique_ptr<dds::Reader<MqttSubscriptions>> subscriptions_reader;
  std::unique_ptr<dds::Writer<PoseCorrection>> correction_writer;
  std::unique_ptr<dds::Writer<WaypointCommand>> waypoint_writer;
};

// map <- odom = (1, 2, 90 deg): the odometry point (a, b) is the map point (1 - b, 2 + a).
TEST_F(GatewayFramesTest, V1RobotStateInTheMapFrameOdometryRawAndWaypointBytesInTheOdometryFrame) {
  ASSERT_NO_FATAL_FAILURE(correct("r1", 1.0, 2.0, kPi / 2, 3));
  MqttTestClient robot(port, "r1");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_TRUE(robot.subscribe("v1/server/r1/cmd"));
  // The robot believes it is at (1, -2.5): 100 and -250 centimetres, no obstacle.
  const std::vector<uint8_t> adv{0x64, 0x00, 0x06, 0xff};
  ASSERT_TRUE(robot.publish("v1/robot/r1/adv", adv));

  // Whichever of correction and message the gateway saw first, the state ends in the map frame.
  const auto state = state_at("r1", 3.5, 3.0);
  ASSERT_TRUE(state);
  EXPECT_FALSE(state->has_heading());
  const auto raw = odometry_with("r1", 3);
  ASSERT_TRUE(raw);
  EXPECT_EQ(raw->odom_pose().x(), 1.0);
  EXPECT_EQ(raw->odom_pose().y(), -2.5);
  EXPECT_FALSE(raw->has_heading());

  // Map (1, 3) is odometry (1, 0): exactly 100 and 0 centimetres, little-endian int16.
  ASSERT_NO_FATAL_FAILURE(send_waypoint("r1", 1, point(1.0, 3.0)));
  const auto cmd = robot.next(10s);
  ASSERT_TRUE(cmd);
  EXPECT_EQ(cmd->topic, "v1/server/r1/cmd");
  EXPECT_EQ(cmd->payload, std::string("\x64\x00\x00\x00", 4));

  // A new correction republishes the state (at the state period) without a word from the robot:
  // identity, so map = odom.
  ASSERT_NO_FATAL_FAILURE(correct("r1", 0.0, 0.0, 0.0, 4));
  ASSERT_TRUE(state_at("r1", 1.0, -2.5));
  ASSERT_TRUE(odometry_with("r1", 4));
  ASSERT_NO_FATAL_FAILURE(send_waypoint("r1", 2, point(1.0, 3.0)));
  const auto identity_cmd = robot.next(10s);
  ASSERT_TRUE(identity_cmd);
  EXPECT_EQ(identity_cmd->payload, std::string("\x64\x00\x2c\x01", 4));  // 100, 300
}

TEST_F(GatewayFramesTest, V2PoseHeadingAndWaypointPathAreConverted) {
  ASSERT_NO_FATAL_FAILURE(correct("r2", 1.0, 2.0, kPi / 2, 1));
  MqttTestClient robot(port, "r2");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_TRUE(robot.subscribe("v2/server/r2/+"));
  ASSERT_TRUE(robot.publish("v2/robot/r2/pose", R"({"x": 1.0, "y": 0.0, "heading": 0.5})"));

  const auto state = state_at("r2", 1.0, 3.0);
  ASSERT_TRUE(state);
  EXPECT_TRUE(state->has_heading());
  EXPECT_NEAR(state->pose().theta(), 0.5 + kPi / 2, 1e-9);
  const auto raw = odometry_with("r2", 1);
  ASSERT_TRUE(raw);
  EXPECT_EQ(raw->odom_pose().x(), 1.0);
  EXPECT_EQ(raw->odom_pose().y(), 0.0);
  EXPECT_EQ(raw->odom_pose().theta(), 0.5);
  EXPECT_TRUE(raw->has_heading());

  ASSERT_NO_FATAL_FAILURE(send_waypoint("r2", 7, point(1.0, 3.0), {point(1.0, 3.0), point(-2.5, 1.0)}));
  std::map<std::string, std::string> got;
  while (got.size() < 2) {
    auto m = robot.next(10s);
    ASSERT_TRUE(m);
    got[m->topic] = m->payload;
  }
  const auto waypoint = nlohmann::json::parse(got["v2/server/r2/waypoint"]);
  EXPECT_EQ(waypoint["seq"], 7);
  EXPECT_NEAR(waypoint["x"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(waypoint["y"].get<double>(), 0.0, 1e-9);
  const auto path = nlohmann::json::parse(got["v2/server/r2/path"]);
  ASSERT_EQ(path["points"].size(), 2u) << got["v2/server/r2/path"];
  EXPECT_NEAR(path["points"][0][0].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(path["points"][0][1].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(path["points"][1][0].get<double>(), -1.0, 1e-9);
  EXPECT_NEAR(path["points"][1][1].get<double>(), 3.5, 1e-9);
}

TEST_F(GatewayFramesTest, FleetDigestsCarryMapFramePosesAndPoints) {
  Inbox<FleetDigest> digests;
  Inbox<FleetPoints> points;
  auto digest_reader = make_inbox_reader(*participant, dds::kFleetDigest, digests);
  auto points_reader = make_inbox_reader(*participant, dds::kFleetPoints, points);
  ASSERT_NO_FATAL_FAILURE(correct("r3", 1.0, 2.0, kPi / 2, 1));
  MqttTestClient robot(port, "r3");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_TRUE(robot.publish("v2/robot/r3/pose", R"({"x": 1.0, "y": 0.0, "heading": 0.0})"));
  ASSERT_TRUE(state_at("r3", 1.0, 3.0));  // the correction is in
  // One beam straight ahead hits at odometry (2, 0): map (1, 4).
  ASSERT_TRUE(robot.publish("v2/robot/r3/scan", R"({"pose": {"x": 1.0, "y": 0.0, "heading": 0.0},
      "angles": [0.0], "ranges": [1.0], "max_range": 4.0})"));

  const auto digest = digests.wait_for(
      [](const FleetDigest& d) {
        for (const DigestRobot& r : d.robots())
          if (r.robot_id() == "r3" && near(r.pose().x(), 1.0) && near(r.pose().y(), 3.0)) return true;
        return false;
      },
      10s);
  ASSERT_TRUE(digest);
  EXPECT_GT(digest->gateway_id().size(), 0u);
  ASSERT_EQ(digest->robots().size(), 1u);
  const DigestRobot& r3 = digest->robots()[0];
  EXPECT_TRUE(r3.has_heading());
  EXPECT_NEAR(r3.pose().theta(), kPi / 2, 1e-9);
  EXPECT_EQ(r3.presence(), PRESENCE_ONLINE);
  EXPECT_GT(r3.last_seen_ns(), 0);

  const auto hit = points.wait_for(
      [](const FleetPoints& f) {
        for (const DigestRobotPoints& r : f.robots())
          if (r.robot_id() == "r3" && !r.points().empty()) return true;
        return false;
      },
      10s);
  ASSERT_TRUE(hit);
  ASSERT_EQ(hit->robots().size(), 1u);
  ASSERT_EQ(hit->robots()[0].points().size(), 1u);
  EXPECT_NEAR(hit->robots()[0].points()[0].x(), 1.0, 1e-5);
  EXPECT_NEAR(hit->robots()[0].points()[0].y(), 4.0, 1e-5);
  EXPECT_EQ(hit->gateway_id(), digest->gateway_id());
}

}  // namespace
}  // namespace slam::testkit

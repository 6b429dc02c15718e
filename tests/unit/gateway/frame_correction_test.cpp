// The gateway's side of the frames contract: the per-robot correction table, reported poses into
// the map frame, and commands into the robot's odometry frame (exact v1 bytes, v2 JSON).
#include "gateway/core/frame_correction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

#include "gateway/core/command_encoder.hpp"

namespace slam::gateway {
namespace {

constexpr double kPi = std::numbers::pi;
// map <- odom: the robot's odometry frame sits at (1, 2) in the map, turned a quarter left. So the
// odometry point (a, b) is the map point (1 - b, 2 + a).
const Pose kQuarterTurn{1.0, 2.0, kPi / 2};

TEST(CorrectionTable, UnknownRobotGetsTheIdentityAtVersionZero) {
  const CorrectionTable table;
  EXPECT_EQ(table.of("r1"), Correction{});
  EXPECT_EQ(table.of("r1").version, 0u);
  EXPECT_EQ(table.of("r1").map_from_odom, Pose{});
}

TEST(CorrectionTable, UpdateSaysWhetherTheCorrectionChanged) {
  CorrectionTable table;
  const Correction first{kQuarterTurn, 1};
  ASSERT_TRUE(table.update("r1", first));
  EXPECT_TRUE(*table.update("r1", first) == false);
  EXPECT_EQ(table.of("r1"), first);
  EXPECT_EQ(table.of("r2"), Correction{});

  const Correction second{{1.5, 2.0, 0.1}, 2};
  const Result<bool> changed = table.update("r1", second);
  ASSERT_TRUE(changed);
  EXPECT_TRUE(*changed);
  EXPECT_EQ(table.of("r1"), second);
}

TEST(CorrectionTable, NonFiniteCorrectionIsAnErrorAndChangesNothing) {
  CorrectionTable table;
  ASSERT_TRUE(table.update("r1", {kQuarterTurn, 1}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Pose& bad : {Pose{nan, 0, 0}, Pose{0, inf, 0}, Pose{0, 0, nan}}) {
    EXPECT_FALSE(table.update("r1", {bad, 2}));
    EXPECT_FALSE(table.update("r2", {bad, 1}));
  }
  EXPECT_EQ(table.of("r1"), (Correction{kQuarterTurn, 1}));
  EXPECT_EQ(table.size(), 1u);
}

TEST(CorrectionTable, FullTableRefusesNewRobotsButStillUpdatesKnownOnes) {
  CorrectionTable table(1);
  ASSERT_TRUE(table.update("r1", {kQuarterTurn, 1}));
  const Result<bool> refused = table.update("r2", {kQuarterTurn, 1});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("max-robots"), std::string::npos) << refused.message();
  EXPECT_TRUE(table.update("r1", {Pose{}, 2}));
  EXPECT_EQ(table.of("r1").version, 2u);
}

TEST(FrameConversion, ReportedPoseWithHeadingMovesAndTurnsIntoTheMapFrame) {
  const Pose map = to_map_frame(kQuarterTurn, {1.0, 0.0, 3.0}, true);
  EXPECT_NEAR(map.x, 1.0, 1e-12);
  EXPECT_NEAR(map.y, 3.0, 1e-12);
  EXPECT_NEAR(map.theta, 3.0 + kPi / 2 - 2 * kPi, 1e-12);  // wrapped into (-pi, pi]
}

TEST(FrameConversion, ReportedPositionWithoutHeadingMovesAndKeepsItsTheta) {
  const Pose map = to_map_frame(kQuarterTurn, {2.0, -1.0, 0.0}, false);
  EXPECT_NEAR(map.x, 2.0, 1e-12);
  EXPECT_NEAR(map.y, 4.0, 1e-12);
  EXPECT_EQ(map.theta, 0.0);
}

TEST(FrameConversion, IdentityCorrectionLeavesEverythingExactlyAsItWas) {
  std::vector<protocol::Point> points{{1.5, -2.0}, {3.0, 0.25}, {0.0, 0.0}};
  const std::vector<protocol::Point> before = points;
  to_odometry_frame(Pose{}, points);
  EXPECT_EQ(points, before);
  EXPECT_EQ(to_map_frame(Pose{}, {1.5, -2.0, 0.3}, true), (Pose{1.5, -2.0, 0.3}));
}

TEST(FrameConversion, MapToOdometryToMapRoundTrips) {
  for (const Pose& correction : {kQuarterTurn, Pose{-3.2, 0.7, -2.9}, Pose{0.05, -0.02, 0.01}}) {
    std::vector<protocol::Point> points{{1.0, 3.0}, {-4.5, 2.25}, {100.0, -80.0}};
    const std::vector<protocol::Point> map = points;
    to_odometry_frame(correction, points);
    for (size_t i = 0; i < points.size(); ++i) {
      const Pose back = to_map_frame(correction, {points[i].x, points[i].y, 0.4}, true);
      EXPECT_NEAR(back.x, map[i].x, 1e-9);
      EXPECT_NEAR(back.y, map[i].y, 1e-9);
      EXPECT_NEAR(back.theta, wrap_angle(correction.theta + 0.4), 1e-12);
    }
  }
}

TEST(FrameConversion, V1WaypointLeavesAsExactOdometryFrameBytes) {
  CommandEncoder encoder{protocol::CodecLimits{}};  // 100 units per metre
  CommandMessages out;
  // Map (1, 3) is odometry (1, 0): 100 and 0 centimetres, little-endian int16.
  ASSERT_TRUE(encoder.encode("r1", Protocol::V1, 1, kQuarterTurn, {1.0, 3.0}, {}, out));
  ASSERT_EQ(out.count, 1u);
  EXPECT_EQ(out.messages[0].topic, "v1/server/r1/cmd");
  EXPECT_EQ(out.messages[0].payload, std::string("\x64\x00\x00\x00", 4));
  // Map (-2.5, 1) is odometry (-1, 3.5): -100 = 0xff9c, 350 = 0x015e.
  ASSERT_TRUE(encoder.encode("r1", Protocol::V1, 2, kQuarterTurn, {-2.5, 1.0}, {}, out));
  EXPECT_EQ(out.messages[0].payload, std::string("\x9c\xff\x5e\x01", 4));
}

TEST(FrameConversion, V1RangeIsCheckedInTheOdometryFrame) {
  CommandEncoder encoder{protocol::CodecLimits{}};
  CommandMessages out;
  // In range in the map, but odometry x = 400 m does not fit an int16 of centimetres.
  const Pose far{-300.0, 0.0, 0.0};
  const auto s = encoder.encode("r1", Protocol::V1, 1, far, {100.0, 0.0}, {}, out);
  EXPECT_EQ(s.reason(), protocol::RejectReason::OutOfRange);
  EXPECT_EQ(out.count, 0u);
}

TEST(FrameConversion, V2WaypointAndPathAreInTheOdometryFrame) {
  CommandEncoder encoder{protocol::CodecLimits{}};
  CommandMessages out;
  // The planner repeats the waypoint at the start of "remaining": the robot still gets it once.
  const std::vector<protocol::Point> remaining{{1.0, 3.0}, {-2.5, 1.0}};
  ASSERT_TRUE(encoder.encode("r2", Protocol::V2, 9, kQuarterTurn, {1.0, 3.0}, remaining, out));
  ASSERT_EQ(out.count, 2u);
  const auto waypoint = nlohmann::json::parse(out.messages[0].payload);
  EXPECT_EQ(waypoint["seq"], 9);
  EXPECT_NEAR(waypoint["x"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(waypoint["y"].get<double>(), 0.0, 1e-9);
  const auto path = nlohmann::json::parse(out.messages[1].payload);
  ASSERT_EQ(path["points"].size(), 2u);
  const std::vector<protocol::Point> odom{{1.0, 0.0}, {-1.0, 3.5}};
  for (size_t i = 0; i < odom.size(); ++i) {
    EXPECT_NEAR(path["points"][i][0].get<double>(), odom[i].x, 1e-9) << i;
    EXPECT_NEAR(path["points"][i][1].get<double>(), odom[i].y, 1e-9) << i;
  }
}

}  // namespace
}  // namespace slam::gateway

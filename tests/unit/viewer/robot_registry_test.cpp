// Robots' corrections (identity until the mapper sent one) and their points, placed in the map
// frame through the correction of the moment they arrived; the fit box covers them.
#include "viewer/core/robot_registry.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace slam::viewer {
namespace {

ObservationData observation(const std::string& id, std::vector<float> xy) {
  ObservationData o;
  o.robot_id = id;
  o.hits_xy = std::move(xy);
  return o;
}

TEST(RobotRegistry, CorrectionIsIdentityUntilTheMapperSendsOne) {
  RobotRegistry robots;
  robots.ingest(observation("r1", {1.0f, 0.0f}));
  const RobotView& r = *robots.find("r1");
  EXPECT_FALSE(r.has_correction);
  EXPECT_EQ(r.map_from_odom().x, 0.0);
  EXPECT_EQ(r.map_from_odom().theta, 0.0);
}

msg::PoseCorrection correction(const std::string& id, uint64_t version, Pose map_from_odom) {
  msg::PoseCorrection c;
  c.robot_id = id;
  c.version = version;
  c.map_from_odom = map_from_odom;
  c.source = CorrectionSource::Loop;
  return c;
}

TEST(RobotRegistry, PointsArePlacedThroughTheCorrectionOfTheirArrival) {
  RobotRegistry robots;
  robots.ingest(correction("r1", 2, {0.0, 0.0, 0.0}));
  robots.ingest(observation("r1", {1.0f, 0.0f}));
  robots.ingest(correction("r1", 3, {5.0, -1.0, std::numbers::pi / 2.0}));
  robots.ingest(observation("r1", {1.0f, 0.0f, 2.0f, 0.0f}));
  const RobotView& r = *robots.find("r1");
  ASSERT_TRUE(r.has_correction);
  EXPECT_EQ(r.correction.version, 3u);
  EXPECT_STREQ(correction_source_name(r.correction.source), "loop closure");
  ASSERT_EQ(r.points.size(), 3u);
  const float* xy = r.points.data();
  EXPECT_FLOAT_EQ(xy[0], 1.0f);
  EXPECT_FLOAT_EQ(xy[1], 0.0f);
  // (1, 0) and (2, 0) rotated a quarter turn and moved by (5, -1): (5, 0) and (5, 1).
  EXPECT_NEAR(xy[2], 5.0f, 1e-6);
  EXPECT_NEAR(xy[3], 0.0f, 1e-6);
  EXPECT_NEAR(xy[4], 5.0f, 1e-6);
  EXPECT_NEAR(xy[5], 1.0f, 1e-6);
  WorldBox box;
  ASSERT_TRUE(robots.bounds(&box));
  EXPECT_NEAR(box.min_x, 1.0, 1e-6);
  EXPECT_NEAR(box.max_x, 5.0, 1e-6);
  EXPECT_NEAR(box.min_y, 0.0, 1e-6);
  EXPECT_NEAR(box.max_y, 1.0, 1e-6);
}

// A heading fix must not swing what the robot saw long before it (the old points were placed
// with the correction that was right for them).
TEST(RobotRegistry, ALaterCorrectionLeavesPlacedPointsWhereTheyAre) {
  RobotRegistry robots;
  robots.ingest(correction("r1", 1, {0.0, 0.0, 0.0}));
  robots.ingest(observation("r1", {4.0f, 0.0f}));
  robots.ingest(correction("r1", 2, {0.0, 0.0, 0.1}));
  const RobotView& r = *robots.find("r1");
  EXPECT_FLOAT_EQ(r.points.data()[0], 4.0f);
  EXPECT_FLOAT_EQ(r.points.data()[1], 0.0f);
  EXPECT_EQ(r.map_from_odom().theta, 0.1);
}

// The pose stream (digests, ten times a second) and the state record (once a second) both carry a
// pose: the one heard last wins, and an older record still brings its counters.
TEST(RobotRegistry, TheNewestPoseWinsBetweenDigestAndStateRecord) {
  RobotRegistry robots;
  msg::RobotPose p;
  p.robot_id = "r1";
  p.pose = {2.0, 1.0, 0.5};
  p.has_heading = true;
  p.online = true;
  p.last_seen_ns = 200;
  robots.ingest(p);
  const RobotView& r = *robots.find("r1");
  ASSERT_TRUE(r.has_state);
  EXPECT_EQ(r.state.pose.x, 2.0);

  msg::RobotState older;
  older.robot_id = "r1";
  older.pose = {1.0, 1.0, 0.0};
  older.last_seen_ns = 150;
  older.messages = 42;
  robots.ingest(std::move(older));
  EXPECT_EQ(r.state.pose.x, 2.0);
  EXPECT_TRUE(r.state.online);
  EXPECT_EQ(r.state.last_seen_ns, 200);
  EXPECT_EQ(r.state.messages, 42u);

  p.pose = {1.5, 1.0, 0.5};
  p.last_seen_ns = 100;  // a gateway that stopped hearing the robot
  robots.ingest(p);
  EXPECT_EQ(r.state.pose.x, 2.0);

  msg::RobotState newer;
  newer.robot_id = "r1";
  newer.pose = {3.0, 1.0, 0.0};
  newer.last_seen_ns = 300;
  robots.ingest(std::move(newer));
  EXPECT_EQ(r.state.pose.x, 3.0);
  EXPECT_FALSE(r.state.online);  // the record's own presence
}

// Points that arrived before the robot's frame was known (no correction yet, or a wrong one an
// operator then fixed) move with the correction that places the frame.
TEST(RobotRegistry, AFirstOrOperatorCorrectionMovesThePointsPlacedBeforeIt) {
  RobotRegistry robots;
  robots.ingest(observation("r1", {1.0f, 0.0f}));
  robots.ingest(correction("r1", 1, {2.0, 0.0, 0.0}));  // the first one
  const RobotView& r = *robots.find("r1");
  EXPECT_NEAR(r.points.data()[0], 3.0f, 1e-6);
  const uint64_t generation = r.points.generation();
  msg::PoseCorrection set_pose = correction("r1", 2, {2.0, 1.0, 0.0});
  set_pose.source = CorrectionSource::Operator;
  robots.ingest(std::move(set_pose));
  EXPECT_NEAR(r.points.data()[0], 3.0f, 1e-6);
  EXPECT_NEAR(r.points.data()[1], 1.0f, 1e-6);
  EXPECT_GT(r.points.generation(), generation);  // the GPU copy is stale
  WorldBox box;
  ASSERT_TRUE(robots.bounds(&box));
  EXPECT_NEAR(box.min_y, 1.0, 1e-6);
}

// A digest written before the gateways dropped a forgotten robot does not bring it back; its next
// message does.
TEST(RobotRegistry, AForgottenRobotStaysForgottenUntilItSpeaksAgain) {
  RobotRegistry robots;
  msg::RobotPose p;
  p.robot_id = "r1";
  p.last_seen_ns = 200;
  robots.ingest(p);
  ASSERT_TRUE(robots.forget("r1"));
  robots.ingest(p);
  msg::RobotState record;
  record.robot_id = "r1";
  record.last_seen_ns = 200;
  robots.ingest(std::move(record));
  EXPECT_EQ(robots.find("r1"), nullptr);
  p.last_seen_ns = 300;
  robots.ingest(p);
  EXPECT_NE(robots.find("r1"), nullptr);
}

}  // namespace
}  // namespace slam::viewer

#include "bridge/core/fleet_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace slam::bridge {
namespace {

std::vector<Vec2> points_of(const RobotView& r) {
  std::vector<Vec2> out;
  r.points.for_each([&out](Vec2 p) { out.push_back(p); });
  return out;
}

TEST(FleetModel, KeepsTheStateOfTheLatestMessageWhateverTheOrderOfArrival) {
  FleetModel fleet(10);
  // Two gateways list the robot: the one that heard it last wins, whichever digest comes last.
  fleet.ingest(msg::RobotPose{"r1", Pose{1, 0, 0}, true, true, 200});
  fleet.ingest(msg::RobotPose{"r1", Pose{5, 0, 0}, true, false, 100});
  EXPECT_EQ(fleet.robots().at("r1").state.pose.x, 1.0);
  EXPECT_TRUE(fleet.robots().at("r1").state.online);
  fleet.ingest(msg::RobotPose{"r1", Pose{2, 0, 0}, true, true, 200});  // same message, newer correction
  EXPECT_EQ(fleet.robots().at("r1").state.pose.x, 2.0);
  fleet.ingest(msg::RobotPose{"r1", Pose{3, 0, 0}, true, false, 300});
  EXPECT_EQ(fleet.robots().at("r1").state.pose.x, 3.0);
  EXPECT_FALSE(fleet.robots().at("r1").state.online);
}

// The gateways' digests written before they dropped a forgotten robot still list it with its last
// message; only a newer message brings it back.
TEST(FleetModel, AForgottenRobotLeavesUntilItSpeaksAgain) {
  FleetModel fleet(10);
  fleet.ingest(msg::RobotPose{"r1", Pose{1, 0, 0}, true, true, 200});
  fleet.ingest(ObservationInput{"r1", {{1.0, 1.0}}});
  const FleetVersions before = fleet.versions();
  fleet.forget("r1");
  EXPECT_TRUE(fleet.robots().empty());
  EXPECT_GT(fleet.versions().robots, before.robots);
  fleet.ingest(msg::RobotPose{"r1", Pose{1, 0, 0}, true, true, 200});
  fleet.ingest(ObservationInput{"r1", {{1.0, 1.0}}});
  fleet.ingest(msg::RobotPath{
      "r1", 0, msg::GoalMode::Planned, msg::GoalStatus::Active, {2.0, 0.0}, {{2.0, 0.0}}, 0, ""});
  EXPECT_TRUE(fleet.robots().empty());
  fleet.ingest(msg::RobotPose{"r1", Pose{1.5, 0, 0}, true, true, 300});
  ASSERT_EQ(fleet.robots().count("r1"), 1u);
  EXPECT_EQ(fleet.robots().at("r1").state.pose.x, 1.5);
}

TEST(FleetModel, KeepsOnlyTheMostRecentPointsPerRobot) {
  FleetModel fleet(3);
  for (int i = 0; i < 5; ++i) fleet.ingest(ObservationInput{"r1", {{static_cast<double>(i), 0.0}}});
  std::vector<double> xs;
  for (const Vec2& p : points_of(fleet.robots().at("r1"))) xs.push_back(p.x);
  std::sort(xs.begin(), xs.end());
  EXPECT_EQ(xs, (std::vector<double>{2.0, 3.0, 4.0}));
}

TEST(FleetModel, CountsChangesPerKind) {
  FleetModel fleet(10);
  const FleetVersions before = fleet.versions();
  fleet.ingest(msg::RobotPose{"r1", Pose{1, 2, 0}, true, true, 5});
  fleet.ingest(
      msg::RobotPath{"r1", 0, msg::GoalMode::Planned, msg::GoalStatus::Active, {3, 4}, {{3, 4}}, 0, ""});
  fleet.ingest(msg::Heartbeat{"mapper", "vm:1", 1, "vm", 0, 2.0, msg::ServiceState::Running, {}}, 100);
  fleet.ingest(ObservationInput{"r1", {}});  // no points: no news
  EXPECT_EQ(fleet.versions().robots, before.robots + 1);
  EXPECT_EQ(fleet.versions().paths, before.paths + 1);
  EXPECT_EQ(fleet.versions().health, before.health + 1);
  EXPECT_EQ(fleet.versions().points, before.points);
  EXPECT_EQ(fleet.services().size(), 1u);
  EXPECT_TRUE(fleet.robots().at("r1").has_state);
}

}  // namespace
}  // namespace slam::bridge

// The ROS 2 face: the grid as OccupancyGrid data, robots as map -> robot transforms, the throttled
// map, and RViz2's goal and initial pose turned into a goal and a set-pose for the chosen robot.
#include "bridge/core/ros_face.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "common/core/cell_class.hpp"

namespace slam::bridge {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

struct RecordingSink final : RosSink {
  void publish_map(const OccupancyGridOut& grid) override { maps.push_back(grid); }
  void publish_tf(const std::vector<TransformOut>& t) override { tfs.push_back(t); }
  void send_goal(const GoalCommand& goal) override { goals.push_back(goal); }
  void send_initial_pose(const std::string& robot_id, const Pose& pose) override {
    poses.emplace_back(robot_id, pose);
  }
  std::vector<OccupancyGridOut> maps;
  std::vector<std::vector<TransformOut>> tfs;
  std::vector<GoalCommand> goals;
  std::vector<std::pair<std::string, Pose>> poses;
};

FleetModel fleet_with(std::initializer_list<std::pair<const char*, Pose>> robots) {
  FleetModel fleet(10);
  for (const auto& [id, pose] : robots) fleet.ingest(msg::RobotPose{id, pose, true, true, 0});
  return fleet;
}

MapView map_of(std::vector<uint8_t> cells, int32_t width, int32_t height) {
  MapView map;
  const msg::GridInfo info{
      static_cast<uint32_t>(width), static_cast<uint32_t>(height), 0.25, {-2.0, 3.0}, 0.0};
  EXPECT_TRUE(map.ingest(msg::GridSnapshot{1, 0, 5 * kSecond, info, std::move(cells)}));
  return map;
}

TEST(RosFace, GridCellsBecomeRosOccupancy) {
  const std::vector<uint8_t> cells = {kCellUnknown,
                                      kCellFree,
                                      kCellOccupied,
                                      kCellFree | kCellInflated,
                                      kCellFree | kCellObstructed,
                                      kCellOccupied | kCellInflated};
  const OccupancyGridOut grid = occupancy_grid(GridGeometry{{-2.0, 3.0}, 0.25, 3, 2}, cells, 7 * kSecond + 5);
  EXPECT_EQ(grid.data, (std::vector<int8_t>{-1, 0, 100, 50, 100, 100}));
  EXPECT_EQ(grid.width, 3u);
  EXPECT_EQ(grid.height, 2u);
  EXPECT_FLOAT_EQ(grid.resolution, 0.25f);
  EXPECT_DOUBLE_EQ(grid.origin.x, -2.0);
  EXPECT_DOUBLE_EQ(grid.origin.y, 3.0);
  EXPECT_EQ(grid.stamp.sec, 7);
  EXPECT_EQ(grid.stamp.nanosec, 5u);
}

TEST(RosFace, EveryRobotIsAFrameUnderTheMap) {
  const FleetModel fleet =
      fleet_with({{"r1", Pose{1.0, 2.0, std::numbers::pi / 2}}, {"r2", Pose{-3.0, 0.5, 0.0}}});
  const auto transforms = robot_transforms(fleet, 3 * kSecond);
  ASSERT_EQ(transforms.size(), 2u);
  EXPECT_EQ(transforms[0].parent, "map");
  EXPECT_EQ(transforms[0].child, "r1");
  EXPECT_DOUBLE_EQ(transforms[0].translation.x, 1.0);
  EXPECT_DOUBLE_EQ(transforms[0].translation.y, 2.0);
  EXPECT_NEAR(transforms[0].rotation.z, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(transforms[0].rotation.w, std::sqrt(0.5), 1e-12);
  EXPECT_EQ(transforms[1].child, "r2");
  EXPECT_DOUBLE_EQ(transforms[1].rotation.w, 1.0);
  EXPECT_EQ(transforms[1].stamp.sec, 3);
}

TEST(RosFace, YawSurvivesTheQuaternion) {
  for (double theta : {0.0, 1.0, -2.5, 3.0}) EXPECT_NEAR(yaw_of(yaw_quaternion(theta)), theta, 1e-12);
}

TEST(RosFace, PosesAreForTheConfiguredRobotOrTheNearest) {
  const FleetModel fleet = fleet_with({{"r1", Pose{0.0, 0.0, 0.0}}, {"r2", Pose{10.0, 0.0, 0.0}}});
  EXPECT_EQ(*robot_for(fleet, "", {8.0, 1.0}), "r2");
  EXPECT_EQ(*robot_for(fleet, "", {1.0, 1.0}), "r1");
  EXPECT_EQ(*robot_for(fleet, "r1", {8.0, 1.0}), "r1");
  EXPECT_FALSE(robot_for(FleetModel(10), "", {0.0, 0.0}));
}

TEST(RosFace, SendsTheWholeMapAtMostOncePerPeriodAndOnlyWhenChanged) {
  RecordingSink sink;
  ChannelPeriods periods;
  periods.map_full_s = 5.0;
  RosFace face(periods, "", sink);
  const FleetModel fleet(10);
  MapView map = map_of({kCellFree, kCellOccupied}, 2, 1);
  face.publish(fleet, map, 0, 0);
  ASSERT_EQ(sink.maps.size(), 1u);
  EXPECT_EQ(sink.maps[0].data, (std::vector<int8_t>{0, 100}));
  face.publish(fleet, map, 10 * kSecond, 0);  // unchanged: nothing however long it waited
  EXPECT_EQ(sink.maps.size(), 1u);
  ASSERT_TRUE(map.ingest(msg::GridSnapshot{
      1, 1, 0, msg::GridInfo{2, 1, 0.25, {0.0, 0.0}, 0.0}, {kCellOccupied, kCellOccupied}}));
  face.publish(fleet, map, 10 * kSecond, 0);  // changed: sent at once, the period long passed
  ASSERT_EQ(sink.maps.size(), 2u);
  ASSERT_TRUE(map.ingest(
      msg::GridSnapshot{1, 2, 0, msg::GridInfo{2, 1, 0.25, {0.0, 0.0}, 0.0}, {kCellFree, kCellFree}}));
  face.publish(fleet, map, 14 * kSecond, 0);  // changed, but only 4 s after the last
  EXPECT_EQ(sink.maps.size(), 2u);
  face.publish(fleet, map, 15 * kSecond, 0);
  ASSERT_EQ(sink.maps.size(), 3u);
  EXPECT_EQ(sink.maps[1].data, (std::vector<int8_t>{100, 100}));
  EXPECT_EQ(sink.maps[2].data, (std::vector<int8_t>{0, 0}));
}

TEST(RosFace, SendsFramesWhenARobotMoved) {
  RecordingSink sink;
  RosFace face(ChannelPeriods{}, "", sink);
  FleetModel fleet = fleet_with({{"r1", Pose{1.0, 0.0, 0.0}}});
  const MapView no_map;
  face.publish(fleet, no_map, 0, 0);
  face.publish(fleet, no_map, kSecond, 0);
  ASSERT_EQ(sink.tfs.size(), 1u);
  fleet.ingest(msg::RobotPose{"r1", Pose{2.0, 0.0, 0.0}, true, true, 0});
  face.publish(fleet, no_map, 2 * kSecond, 0);
  ASSERT_EQ(sink.tfs.size(), 2u);
  EXPECT_DOUBLE_EQ(sink.tfs[1][0].translation.x, 2.0);
  EXPECT_TRUE(sink.maps.empty());
}

TEST(RosFace, GoalPoseBecomesAPlannedGoalForTheChosenRobot) {
  RecordingSink sink;
  RosFace face(ChannelPeriods{}, "", sink);
  const FleetModel fleet = fleet_with({{"r1", Pose{0.0, 0.0, 0.0}}, {"r2", Pose{10.0, 0.0, 0.0}}});
  ASSERT_TRUE(face.goal_pose(fleet, RosPoseInput{"map", {9.0, 2.0}, {}}));
  ASSERT_EQ(sink.goals.size(), 1u);
  EXPECT_EQ(sink.goals[0].robot_id, "r2");
  EXPECT_EQ(sink.goals[0].mode, msg::GoalMode::Planned);
  EXPECT_DOUBLE_EQ(sink.goals[0].target.x, 9.0);
  EXPECT_DOUBLE_EQ(sink.goals[0].target.y, 2.0);
}

TEST(RosFace, RefusesPosesInAnUnknownFrameOrWithNoRobot) {
  RecordingSink sink;
  RosFace face(ChannelPeriods{}, "", sink);
  const FleetModel fleet = fleet_with({{"r1", Pose{0.0, 0.0, 0.0}}});
  const Status s = face.goal_pose(fleet, RosPoseInput{"odom", {1.0, 0.0}, {}});
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("odom"), std::string::npos);
  EXPECT_FALSE(face.initial_pose(FleetModel(10), RosPoseInput{"map", {1.0, 0.0}, {}}));
  EXPECT_TRUE(sink.goals.empty());
  EXPECT_TRUE(sink.poses.empty());
}

TEST(RosFace, InitialPoseSetsTheConfiguredRobotsPose) {
  RecordingSink sink;
  RosFace face(ChannelPeriods{}, "r1", sink);
  const FleetModel fleet = fleet_with({{"r1", Pose{0.0, 0.0, 0.0}}, {"r2", Pose{10.0, 0.0, 0.0}}});
  ASSERT_TRUE(face.initial_pose(fleet, RosPoseInput{"", {9.0, 1.0}, yaw_quaternion(1.25)}));
  ASSERT_EQ(sink.poses.size(), 1u);
  EXPECT_EQ(sink.poses[0].first, "r1");
  EXPECT_DOUBLE_EQ(sink.poses[0].second.x, 9.0);
  EXPECT_DOUBLE_EQ(sink.poses[0].second.y, 1.0);
  EXPECT_NEAR(sink.poses[0].second.theta, 1.25, 1e-12);
}

}  // namespace
}  // namespace slam::bridge

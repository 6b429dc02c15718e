#include "bridge/core/foxglove_messages.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "common/core/cell_class.hpp"

namespace slam::bridge {
namespace {

using nlohmann::json;

TEST(FoxgloveMessages, MapsCellClassesToRosOccupancy) {
  EXPECT_EQ(occupancy_of(kCellUnknown), -1);
  EXPECT_EQ(occupancy_of(kCellFree), 0);
  EXPECT_EQ(occupancy_of(kCellFree | kCellInflated), 50);
  EXPECT_EQ(occupancy_of(kCellOccupied), 100);
  EXPECT_EQ(occupancy_of(kCellUnknown | kCellObstructed), 100);
}

TEST(FoxgloveMessages, AGridRegionStartsAtItsCorner) {
  const GridGeometry g{{-1.0, -2.0}, 0.5, 4, 3};
  std::vector<uint8_t> cells(12, kCellFree);
  cells[1 * 4 + 2] = kCellOccupied;
  const json j = json::parse(grid_message(g, cells, CellBox{2, 1, 2, 2}, 1'500'000'000));
  EXPECT_EQ(j["frame_id"], "map");
  EXPECT_EQ(j["timestamp"]["sec"], 1);
  EXPECT_EQ(j["timestamp"]["nsec"], 500'000'000);
  EXPECT_DOUBLE_EQ(j["pose"]["position"]["x"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["pose"]["position"]["y"].get<double>(), -1.5);
  EXPECT_EQ(j["column_count"], 2);
  EXPECT_EQ(j["row_stride"], 2);
  // Cells (2,1)=100, (3,1)=0, (2,2)=0, (3,2)=0 as int8: 0x64 00 00 00.
  EXPECT_EQ(j["data"], "ZAAAAA==");
}

TEST(FoxgloveMessages, RobotsWithAHeadingAreArrowsOthersSpheres) {
  FleetModel fleet(0);
  fleet.ingest(msg::RobotPose{"v2", Pose{1, 2, 0.5}, true, true, 0});
  fleet.ingest(msg::RobotPose{"v1", Pose{3, 4, 0}, false, false, 0});
  const json j = json::parse(robots_message(fleet, 0));
  ASSERT_EQ(j["entities"].size(), 2u);
  const json& v1 = j["entities"][0];  // sorted by id
  const json& v2 = j["entities"][1];
  EXPECT_EQ(v1["id"], "robot/v1");
  EXPECT_EQ(v1["arrows"].size(), 0u);
  ASSERT_EQ(v1["spheres"].size(), 1u);
  EXPECT_LT(v1["spheres"][0]["color"]["a"].get<double>(), 1.0);  // offline: faded
  ASSERT_EQ(v2["arrows"].size(), 1u);
  EXPECT_NEAR(v2["arrows"][0]["pose"]["orientation"]["z"].get<double>(), std::sin(0.25), 1e-12);
  EXPECT_EQ(v2["texts"][0]["text"], "v2");
}

TEST(FoxgloveMessages, TransformsGoFromTheMapToEachRobot) {
  FleetModel fleet(0);
  fleet.ingest(msg::RobotPose{"r1", Pose{1, 2, 0}, true, true, 0});
  const json j = json::parse(transforms_message(fleet, 0));
  ASSERT_EQ(j["transforms"].size(), 1u);
  EXPECT_EQ(j["transforms"][0]["parent_frame_id"], "map");
  EXPECT_EQ(j["transforms"][0]["child_frame_id"], "r1");
  EXPECT_EQ(j["transforms"][0]["translation"]["y"], 2.0);
}

TEST(FoxgloveMessages, AnActivePathRunsFromTheRobotAndAFinishedOneIsCleared) {
  FleetModel fleet(0);
  fleet.ingest(msg::RobotPose{"r1", Pose{0, 0, 0}, true, true, 0});
  fleet.ingest(msg::RobotPath{
      "r1", 0, msg::GoalMode::Planned, msg::GoalStatus::Active, {2, 2}, {{1, 0}, {2, 0}, {2, 2}}, 1, ""});
  json j = json::parse(paths_message(fleet, 0));
  ASSERT_EQ(j["entities"][0]["lines"].size(), 1u);
  EXPECT_EQ(j["entities"][0]["lines"][0]["points"].size(), 3u);  // robot, then waypoints from `current`
  EXPECT_EQ(j["entities"][0]["spheres"].size(), 1u);
  EXPECT_EQ(j["entities"][0]["metadata"][1]["value"], "planned");
  EXPECT_EQ(j["entities"][0]["metadata"][2]["value"], "active");
  fleet.ingest(msg::RobotPath{"r1", 0, msg::GoalMode::Planned, msg::GoalStatus::Reached, {2, 2}, {}, 0, ""});
  j = json::parse(paths_message(fleet, 0));
  EXPECT_EQ(j["entities"][0]["lines"].size(), 0u);
  EXPECT_EQ(j["entities"][0]["spheres"].size(), 0u);
}

TEST(FoxgloveMessages, PointsAreTwelveBytesEach) {
  FleetModel fleet(10);
  fleet.ingest(ObservationInput{"r1", {{1, 2}, {3, 4}}});
  const json j = json::parse(points_message(fleet, 0));
  EXPECT_EQ(j["point_stride"], 12);
  EXPECT_EQ(j["data"].get<std::string>().size(), 32u);  // 24 bytes in base64
}

TEST(FoxgloveMessages, HealthSaysHowLongAgoEachServiceWasHeard) {
  FleetModel fleet(0);
  fleet.ingest(msg::Heartbeat{"mapper", "vm:1", 1, "vm", 0, 2.0, msg::ServiceState::Running, {}},
               1'000'000'000);
  const json j = json::parse(health_message(fleet, 3'500'000'000, 0));
  ASSERT_EQ(j["services"].size(), 1u);
  EXPECT_EQ(j["services"][0]["service"], "mapper");
  EXPECT_EQ(j["services"][0]["state"], "running");
  EXPECT_DOUBLE_EQ(j["services"][0]["last_heard_s"].get<double>(), 2.5);
}

TEST(FoxgloveMessages, AlertsListEachAlertsLatestState) {
  FleetModel fleet(1);
  fleet.ingest(msg::Alert{"offline/r1", msg::AlertKind::RobotOffline, "r1", true, 2'000'000'000,
                          2'000'000'000, "r1 is offline", "p1"});
  fleet.ingest(msg::Alert{"offline/r1", msg::AlertKind::RobotOffline, "r1", false, 2'000'000'000,
                          5'000'000'000, "r1 is back", "p1"});
  fleet.ingest(msg::Alert{"battery/r2", msg::AlertKind::BatteryLow, "r2", true, 3'000'000'000, 3'000'000'000,
                          "r2 at 9 %", "p1"});
  const json j = json::parse(alerts_message(fleet, 6'000'000'000));
  ASSERT_EQ(j["alerts"].size(), 2u);
  EXPECT_EQ(j["alerts"][0]["alert_id"], "battery/r2");
  EXPECT_EQ(j["alerts"][0]["active"], true);
  EXPECT_EQ(j["alerts"][0]["kind"], "battery_low");
  EXPECT_EQ(j["alerts"][1]["alert_id"], "offline/r1");
  EXPECT_EQ(j["alerts"][1]["active"], false);
  EXPECT_EQ(j["alerts"][1]["message"], "r1 is back");
  EXPECT_EQ(j["alerts"][1]["raised"]["sec"], 2);
  EXPECT_EQ(j["alerts"][1]["changed"]["sec"], 5);
  EXPECT_EQ(j["timestamp"]["sec"], 6);
}

}  // namespace
}  // namespace slam::bridge

// The bridge against a client no one here wrote: Foxglove's own FoxgloveClient (Node,
// @foxglove/ws-protocol, pinned in tests/node/package-lock.json) connects to the bridge of a running
// fleet (mosquitto, gateway, mapper, planner, one simulated robot in the empty world), lists and
// subscribes to every channel, checks every message against @foxglove/schemas' JSON schemas, calls
// the path service and publishes a goal that must move the robot (tests/node/foxglove_client_test.mjs).
// And the bridge's ROS 2 face seen by a plain Fast DDS participant with the idl/ros2.idl types: ROS 2's
// type names and QoS on rt/map and rt/tf, and RViz2's goal and initial pose turned into the fleet's.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "common/core/cell_class.hpp"
#include "common/core/grid_tiles.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;

// A cell class as ROS 2's occupancy, written here from the spec: -1 unknown, 0 free, 50 free but
// inflated, 100 occupied or obstructed.
int8_t ros_occupancy(uint8_t cell) {
  if ((cell & kCellObstructed) || (cell & kCellStateMask) == kCellOccupied) return 100;
  if ((cell & kCellStateMask) != kCellFree) return -1;
  return (cell & kCellInflated) ? 50 : 0;
}

// The mapper's cells as they were at `stamp_ns`: the snapshot of that stamp, or the last snapshot
// before it with the patches that followed it up to that stamp. Nothing when neither was seen.
std::optional<std::vector<uint8_t>> mapper_cells_at(const std::vector<GridSnapshot>& snapshots,
                                                    const std::vector<GridTiles>& patches, int64_t stamp_ns) {
  const GridSnapshot* base = nullptr;
  for (const GridSnapshot& s : snapshots)
    if (s.stamp_ns() <= stamp_ns && (!base || s.version() >= base->version())) base = &s;
  if (!base) return std::nullopt;
  std::vector<uint8_t> cells = base->cells();
  uint64_t version = base->version();
  if (base->stamp_ns() == stamp_ns) return cells;
  for (bool applied = true; applied;) {
    applied = false;
    for (const GridTiles& t : patches) {
      if (t.layout_id() != base->layout_id() || t.version() != version + 1) continue;
      TilePatchView patch{t.tile_side(), t.encoding(), t.tiles(), t.data()};
      if (!apply_tiles(patch, cells, static_cast<int32_t>(base->info().width()),
                       static_cast<int32_t>(base->info().height())))
        return std::nullopt;
      version = t.version();
      if (t.stamp_ns() == stamp_ns) return cells;
      applied = true;
    }
  }
  return std::nullopt;
}

bool node_installed() {
  return std::system("node --version > /dev/null 2>&1") == 0;
}

TEST(BridgeTest, FoxgloveClientSeesTheFleetAndDrivesARobot) {
  if (!node_installed())
    GTEST_SKIP() << "node is not installed (apt-get install nodejs): no Foxglove client to run";
  const std::string node_dir = SLAM_NODE_TESTS_DIR;
  ASSERT_TRUE(std::filesystem::exists(node_dir + "/node_modules/@foxglove/ws-protocol"))
      << "the pinned npm packages are missing: run scripts/setup.sh (npm ci in tests/node)";

  testkit::DomainLease lease;
  testkit::ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  // The mapper's grid as it goes out, to compare with the OccupancyGrid the client decodes.
  auto participant = dds::Participant::create(lease.id(), "bridge_test");
  ASSERT_TRUE(participant) << participant.message();
  testkit::Inbox<GridSnapshot> snapshots;
  testkit::Inbox<GridTiles> patches;
  auto snapshot_reader = testkit::make_inbox_reader(**participant, dds::kGridSnapshot, snapshots);
  auto patch_reader = testkit::make_inbox_reader(**participant, dds::kGridTiles, patches);
  const int mqtt_port = group.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(mqtt_port);
  const int ws_port = testkit::free_tcp_port();
  group.start("bridge", {testkit::bin_path("slam-bridge"), "--domain", domain, "--bind",
                         "127.0.0.1:" + std::to_string(ws_port), "--periods-map-full-s", "1"});
  group.start("gateway", {testkit::bin_path("slam-gateway"), "--domain", domain, "--broker", broker});
  group.start("mapper", {testkit::bin_path("slam-mapper"), "--domain", domain, "--store",
                         group.dir() + "/map.db", "--snapshot-period", "1"});
  group.start("planner", {testkit::bin_path("slam-planner"), "--domain", domain, "--goal-store",
                          group.dir() + "/goals.json"});
  group.start("simulator", {testkit::bin_path("slam-simulator"), "--domain", domain, "--broker", broker,
                            "--world", "empty", "--robots", "1", "--drift", "0", "--seed", "5"});
  ASSERT_TRUE(testkit::wait_port_open(ws_port, 20s)) << group.log("bridge");

  const std::string grid_file = group.dir() + "/ros_grid.json";
  group.start("client", {"node", node_dir + "/foxglove_client_test.mjs",
                         "ws://127.0.0.1:" + std::to_string(ws_port), "90", grid_file});
  const int code = group.wait_exit("client", 120s);
  ASSERT_EQ(code, 0) << group.log("client");
  EXPECT_TRUE(group.running("bridge")) << group.log("bridge");

  // The cells the client decoded from nav_msgs/msg/OccupancyGrid CDR are the mapper's at that stamp.
  std::ifstream in(grid_file);
  ASSERT_TRUE(in) << "the client wrote no decoded grid";
  const nlohmann::json grid = nlohmann::json::parse(in);
  const int64_t stamp_ns = std::stoll(grid["stamp_ns"].get<std::string>());
  const auto expected = mapper_cells_at(snapshots.items(), patches.items(), stamp_ns);
  ASSERT_TRUE(expected) << "no mapper grid seen with stamp " << stamp_ns;
  const auto decoded = grid["data"].get<std::vector<int>>();
  ASSERT_EQ(decoded.size(), expected->size());
  size_t mismatched = 0;
  for (size_t i = 0; i < decoded.size(); ++i)
    if (decoded[i] != ros_occupancy((*expected)[i])) ++mismatched;
  EXPECT_EQ(mismatched, 0u) << "of " << decoded.size() << " cells";
  EXPECT_NE(std::count(decoded.begin(), decoded.end(), 0), 0) << "no free cell: the robot mapped nothing";
}

TEST(BridgeTest, Ros2WireCarriesTheMapFramesAndGoals) {
  // The names ROS 2 (rmw_fastrtps, rmw_cyclonedds) gives these types on DDS: a reader matches a
  // writer only with the same type name.
  EXPECT_STREQ(nav_msgs::msg::dds_::OccupancyGrid_PubSubType().getName(),
               "nav_msgs::msg::dds_::OccupancyGrid_");
  EXPECT_STREQ(tf2_msgs::msg::dds_::TFMessage_PubSubType().getName(), "tf2_msgs::msg::dds_::TFMessage_");
  EXPECT_STREQ(geometry_msgs::msg::dds_::PoseStamped_PubSubType().getName(),
               "geometry_msgs::msg::dds_::PoseStamped_");
  EXPECT_STREQ(geometry_msgs::msg::dds_::PoseWithCovarianceStamped_PubSubType().getName(),
               "geometry_msgs::msg::dds_::PoseWithCovarianceStamped_");

  testkit::DomainLease lease;
  testkit::ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  const int mqtt_port = group.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(mqtt_port);
  group.start("bridge",
              {testkit::bin_path("slam-bridge"), "--domain", domain, "--bind",
               "127.0.0.1:" + std::to_string(testkit::free_tcp_port()), "--periods-map-full-s", "1"});
  group.start("gateway", {testkit::bin_path("slam-gateway"), "--domain", domain, "--broker", broker});
  group.start("mapper", {testkit::bin_path("slam-mapper"), "--domain", domain, "--store",
                         group.dir() + "/map.db", "--snapshot-period", "1"});
  group.start("simulator", {testkit::bin_path("slam-simulator"), "--domain", domain, "--broker", broker,
                            "--world", "empty", "--robots", "2", "--drift", "0", "--seed", "5"});

  auto participant = dds::Participant::create(lease.id(), "bridge_test");
  ASSERT_TRUE(participant) << participant.message();
  auto& p = **participant;
  testkit::Inbox<RobotState> states;
  testkit::Inbox<GridSnapshot> snapshots;
  testkit::Inbox<tf2_msgs::msg::dds_::TFMessage_> frames;
  testkit::Inbox<NavGoal> goals;
  testkit::Inbox<InitialPose> initial_poses;
  auto state_reader = testkit::make_inbox_reader(p, dds::kRobotState, states);
  auto snapshot_reader = testkit::make_inbox_reader(p, dds::kGridSnapshot, snapshots);
  auto tf_reader = testkit::make_inbox_reader(p, dds::kRosTf, frames);
  auto goal_reader = testkit::make_inbox_reader(p, dds::kNavGoal, goals);
  auto initial_pose_reader = testkit::make_inbox_reader(p, dds::kInitialPose, initial_poses);

  // rt/tf: map -> each robot, under the robots' ids.
  std::set<std::string> robots;
  ASSERT_TRUE(testkit::wait_until(
      [&] {
        for (const RobotState& s : states.items()) robots.insert(s.robot_id().to_string());
        return robots.size() == 2;
      },
      60s))
      << group.log("simulator");
  std::set<std::string> framed;
  ASSERT_TRUE(testkit::wait_until(
      [&] {
        for (const auto& m : frames.items())
          for (const auto& t : m.transforms()) {
            EXPECT_EQ(t.header().frame_id(), "map");
            framed.insert(t.child_frame_id());
          }
        return framed == robots;
      },
      30s))
      << group.log("bridge");

  // rt/map: a reader asking for reliable, transient-local (as RViz2 must for Nav2's map) matches
  // only a writer offering both, and gets the map even though it joins after the bridge wrote it.
  ASSERT_TRUE(snapshots.wait_size(1, 60s)) << group.log("mapper");
  testkit::Inbox<nav_msgs::msg::dds_::OccupancyGrid_> maps;
  const dds::Topic<nav_msgs::msg::dds_::OccupancyGrid_, nav_msgs::msg::dds_::OccupancyGrid_PubSubType>
      late_map{{topics::kRosMap.name, topics::QosSpec{true, true, 1, 0}}};
  ASSERT_TRUE(frames.wait_size(frames.size() + 1, 30s));  // the bridge's loop ran after the snapshot
  auto map_reader = testkit::make_inbox_reader(p, late_map, maps);
  auto map = maps.wait_for([](const auto&) { return true; }, 30s);
  ASSERT_TRUE(map) << group.log("bridge");
  EXPECT_EQ(map->header().frame_id(), "map");
  EXPECT_GT(map->info().width(), 0u);
  EXPECT_GT(map->info().resolution(), 0.0f);
  EXPECT_EQ(map->data().size(), static_cast<size_t>(map->info().width()) * map->info().height());
  EXPECT_DOUBLE_EQ(map->info().origin().orientation().w(), 1.0);
  for (int8_t cell : map->data())
    ASSERT_TRUE(cell == -1 || cell == 0 || cell == 50 || cell == 100) << int(cell);

  // RViz2's "2D Goal Pose" beside one robot: a planned NavGoal for that robot, the nearest.
  const RobotState near = *states.last([](const RobotState&) { return true; });
  geometry_msgs::msg::dds_::PoseStamped_ goal_pose;
  goal_pose.header().frame_id("map");
  goal_pose.pose().position().x(near.pose().x() + 0.5);
  goal_pose.pose().position().y(near.pose().y());
  goal_pose.pose().orientation().w(1.0);
  auto goal_writer = testkit::make_test_writer(p, dds::kRosGoalPose);
  const auto is_ros_goal = [&](const NavGoal& g) {
    return g.robot_id() == near.robot_id() && g.mode() == GOAL_PLANNED &&
           std::abs(g.target().x() - goal_pose.pose().position().x()) < 1e-9;
  };
  ASSERT_TRUE(testkit::wait_until(
      [&] {
        goal_writer->write(goal_pose);  // until the bridge's reader matched
        return goals.wait_for(is_ros_goal, 500ms).has_value();
      },
      30s))
      << group.log("bridge");

  // RViz2's "2D Pose Estimate": the mapper's set-pose request for the same robot.
  geometry_msgs::msg::dds_::PoseWithCovarianceStamped_ initial;
  initial.header().frame_id("map");
  initial.pose().pose().position().x(near.pose().x());
  initial.pose().pose().position().y(near.pose().y() + 0.25);
  initial.pose().pose().orientation().z(std::sin(0.5));
  initial.pose().pose().orientation().w(std::cos(0.5));
  auto initial_writer = testkit::make_test_writer(p, dds::kRosInitialPose);
  const auto is_ros_pose = [&](const InitialPose& i) {
    return i.robot_id() == near.robot_id() && std::abs(i.pose().theta() - 1.0) < 1e-9 &&
           std::abs(i.pose().y() - initial.pose().pose().position().y()) < 1e-9;
  };
  ASSERT_TRUE(testkit::wait_until(
      [&] {
        initial_writer->write(initial);
        return initial_poses.wait_for(is_ros_pose, 500ms).has_value();
      },
      30s))
      << group.log("bridge");
  EXPECT_TRUE(group.running("bridge")) << group.log("bridge");
}

TEST(BridgeTest, NoRosLeavesTheRosTopicsUnwritten) {
  testkit::DomainLease lease;
  testkit::ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  auto participant = dds::Participant::create(lease.id(), "bridge_test");
  ASSERT_TRUE(participant) << participant.message();
  testkit::Inbox<Heartbeat> beats;
  auto beat_reader = testkit::make_inbox_reader(**participant, dds::kHeartbeat, beats);
  auto map_reader = dds::make_reader(**participant, dds::kRosMap);
  ASSERT_TRUE(map_reader) << map_reader.message();
  group.start("bridge", {testkit::bin_path("slam-bridge"), "--domain", domain, "--bind",
                         "127.0.0.1:" + std::to_string(testkit::free_tcp_port()), "--no-ros"});
  // Once the bridge's heartbeat arrived, its participant is discovered; its writers with it.
  ASSERT_TRUE(beats.wait_for([](const Heartbeat& h) { return h.service() == "bridge"; }, 30s))
      << group.log("bridge");
  ASSERT_TRUE(beats.wait_size(beats.size() + 2, 30s));
  EXPECT_EQ((*map_reader)->matched_writers(), 0);
}

}  // namespace
}  // namespace slam

// VDA 5050 against a client no one here wrote: vda-5050-lib's AgvController with its VirtualAgvAdapter
// (Node, pinned in tests/node/package-lock.json; tests/node/vda5050_agv_test.mjs) joins a mixed fleet
// (mosquitto, gateway, mapper, planner, one simulated v1 robot mapping the empty world), shows up as a
// fleet robot, takes the planner's path for a goal as an order and its updates, and reaches the goal;
// a stop pauses it (startPause) and the same goal again resumes its order (stopPause), a goal elsewhere
// cancels the held order for a new one; orders a robot rejects are reported with its reason, and not
// sent forever; a robot whose connection breaks (the broker's last will) is marked offline.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;

constexpr const char* kRobot = "SlamTest:agv-1";  // <manufacturer>:<serialNumber>

NavGoal make_goal(const std::string& robot, std::uint64_t id, GoalMode mode, double x, double y) {
  NavGoal goal;
  goal.robot_id(robot);
  goal.goal_id(id);
  goal.mode(mode);
  Point2 target;
  target.x(x);
  target.y(y);
  goal.target(target);
  return goal;
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++count;
  return count;
}

bool node_ready() {
  return std::system("node --version > /dev/null 2>&1") == 0 &&
         std::filesystem::exists(std::string(SLAM_NODE_TESTS_DIR) + "/node_modules/vda-5050-lib");
}

class Vda5050Test : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!node_ready())
      GTEST_SKIP()
          << "node or the pinned npm packages are missing: run scripts/setup.sh (npm ci in tests/node)";
    auto p = dds::Participant::create(lease_.id(), "vda5050_test");
    ASSERT_TRUE(p) << p.message();
    participant_ = std::move(*p);
    state_reader_ = testkit::make_inbox_reader(*participant_, dds::kRobotState, states_);
    path_reader_ = testkit::make_inbox_reader(*participant_, dds::kRobotPath, paths_);
    broker_ = "tcp://127.0.0.1:" + std::to_string(group_.start_mosquitto());
    group_.start("gateway", {testkit::bin_path("slam-gateway"), "--domain", domain(), "--broker", broker_,
                             "--no-share"});
  }

  std::string domain() const { return std::to_string(lease_.id()); }

  // The virtual AGV on map "office" at (x, y), switched to `operating_mode` once started (none: the
  // library's AUTOMATIC).
  void start_agv(double x, double y, const std::string& operating_mode = "") {
    const std::string url = "mqtt://" + broker_.substr(std::string("tcp://").size());
    std::vector<std::string> command{"node",
                                     std::string(SLAM_NODE_TESTS_DIR) + "/vda5050_agv_test.mjs",
                                     url,
                                     "SlamTest",
                                     "agv-1",
                                     std::to_string(x),
                                     std::to_string(y),
                                     "office"};
    if (!operating_mode.empty()) command.push_back(operating_mode);
    group_.start("agv", command);
  }

  std::optional<RobotState> wait_state(const std::function<bool(const RobotState&)>& pred,
                                       std::chrono::milliseconds timeout) {
    return states_.wait_for([&](const RobotState& s) { return s.robot_id() == kRobot && pred(s); }, timeout);
  }

  testkit::DomainLease lease_;
  testkit::ProcessGroup group_;
  std::string broker_;
  std::unique_ptr<dds::Participant> participant_;
  testkit::Inbox<RobotState> states_;
  testkit::Inbox<RobotPath> paths_;
  std::unique_ptr<dds::Reader<RobotState>> state_reader_;
  std::unique_ptr<dds::Reader<RobotPath>> path_reader_;
};

TEST_F(Vda5050Test, VirtualAgvReachesAPlannedGoalAndASquareThroughOrders) {
  group_.start("mapper", {testkit::bin_path("slam-mapper"), "--domain", domain(), "--store",
                          group_.dir() + "/map.db", "--snapshot-period", "1"});
  group_.start("planner", {testkit::bin_path("slam-planner"), "--domain", domain(), "--no-share",
                           "--goal-store", group_.dir() + "/goals.json"});
  group_.start("simulator", {testkit::bin_path("slam-simulator"), "--domain", domain(), "--broker", broker_,
                             "--world", "empty", "--robots", "1", "--drift", "0", "--seed", "5"});
  start_agv(2.0, 2.0);

  const auto joined = wait_state(
      [](const RobotState& s) {
        return s.presence() == PRESENCE_ONLINE && std::abs(s.pose().x() - 2.0) < 0.01 &&
               std::abs(s.pose().y() - 2.0) < 0.01;
      },
      60s);
  ASSERT_TRUE(joined) << group_.log("agv") << group_.log("gateway");
  EXPECT_GT(joined->battery(), 0.9f);
  EXPECT_EQ(joined->status().to_string(), "AUTOMATIC");

  auto goals = dds::make_writer(*participant_, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();
  ASSERT_TRUE((*goals)->wait_for_readers(30s));
  NavGoal goal;
  goal.robot_id(kRobot);
  goal.goal_id(1);
  goal.mode(GOAL_PLANNED);
  Point2 target;
  target.x(3.0);
  target.y(8.0);
  goal.target(target);
  ASSERT_TRUE((*goals)->write(goal));

  const auto reached = paths_.wait_for(
      [](const RobotPath& p) {
        return p.robot_id() == kRobot && p.goal_id() == 1 && p.status() == GOAL_STATUS_REACHED;
      },
      120s);
  ASSERT_TRUE(reached) << group_.log("agv") << group_.log("planner") << group_.log("gateway");
  const auto there = wait_state(
      [](const RobotState& s) { return std::hypot(s.pose().x() - 3.0, s.pose().y() - 8.0) < 0.2; }, 10s);
  EXPECT_TRUE(there) << "the planner saw the goal reached, but no state of the robot there";
  // The robot took our order: its own log names it. (The planner counts the goal reached within its
  // tolerance and holds the robot there, which may be before the robot reports the order's last node;
  // the square below shows the nodes passed.)
  EXPECT_NE(group_.log("agv").find("order slam-"), std::string::npos) << group_.log("agv");

  // A square of four waypoints: one order released a corner at a time, extended by an update stitched
  // at the last corner reached (its log shows update 4: the way back to the first corner).
  goal.goal_id(2);
  goal.mode(GOAL_SQUARE);
  target.x(3.0);
  target.y(6.0);
  goal.target(target);
  goal.square_size(1.5);
  goal.square_anchor(SQUARE_CORNER);
  ASSERT_TRUE((*goals)->write(goal));
  const auto square = paths_.wait_for(
      [](const RobotPath& p) {
        return p.robot_id() == kRobot && p.goal_id() == 2 && p.status() == GOAL_STATUS_REACHED;
      },
      120s);
  ASSERT_TRUE(square) << group_.log("agv") << group_.log("gateway");
  const std::string agv = group_.log("agv");
  EXPECT_NE(agv.find(" update 4"), std::string::npos) << agv;
  EXPECT_EQ(agv.find("error "), std::string::npos) << agv;
}

// Stop goals reach the gateway as the robot's own position, as for v1/v2 robots, and so do the traffic
// rules' holds: the robot is paused with its order kept; the same goal again goes on to the same node,
// so the pause ends and the order goes on; a goal elsewhere cancels the held order for a new one.
TEST_F(Vda5050Test, AStopPausesTheVirtualAgvAndItsOrderResumesOrIsCancelled) {
  group_.start("planner", {testkit::bin_path("slam-planner"), "--domain", domain(), "--no-share",
                           "--goal-store", group_.dir() + "/goals.json"});
  start_agv(1.0, 1.0);
  ASSERT_TRUE(wait_state([](const RobotState& s) { return s.presence() == PRESENCE_ONLINE; }, 60s))
      << group_.log("agv") << group_.log("gateway");
  auto goals = dds::make_writer(*participant_, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();
  ASSERT_TRUE((*goals)->wait_for_readers(30s));

  // Straight on to (1, 9); stopped on the way.
  ASSERT_TRUE((*goals)->write(make_goal(kRobot, 1, GOAL_DIRECT, 1.0, 9.0)));
  ASSERT_TRUE(wait_state([](const RobotState& s) { return s.pose().y() > 2.5; }, 30s)) << group_.log("agv");
  ASSERT_TRUE((*goals)->write(make_goal(kRobot, 2, GOAL_STOP, 0.0, 0.0)));
  ASSERT_TRUE(
      testkit::wait_until([&] { return group_.log("agv").find("\npaused") != std::string::npos; }, 10s))
      << group_.log("agv") << group_.log("gateway");

  // The same goal again: the order it holds goes on, unpaused, to its node.
  ASSERT_TRUE((*goals)->write(make_goal(kRobot, 3, GOAL_DIRECT, 1.0, 9.0)));
  ASSERT_TRUE(paths_.wait_for(
      [](const RobotPath& p) {
        return p.robot_id() == kRobot && p.goal_id() == 3 && p.status() == GOAL_STATUS_REACHED;
      },
      60s))
      << group_.log("agv") << group_.log("gateway");
  std::string agv = group_.log("agv");
  EXPECT_EQ(count_of(agv, "unpaused"), 1u) << agv;
  EXPECT_EQ(count_of(agv, "order slam-"), 1u) << "one order, resumed: " << agv;

  // Back towards (1, 1), stopped on the way, then a goal elsewhere: the held order is cancelled and a
  // new one driven. (The planner may hold the robot where it reached goal 3, which pauses it too.)
  states_.clear();  // from here on, states on the way back
  ASSERT_TRUE((*goals)->write(make_goal(kRobot, 4, GOAL_DIRECT, 1.0, 1.0)));
  ASSERT_TRUE(wait_state([](const RobotState& s) { return s.pose().y() < 7.5; }, 30s)) << group_.log("agv");
  const std::size_t pauses = count_of(group_.log("agv"), "\npaused");
  ASSERT_TRUE((*goals)->write(make_goal(kRobot, 5, GOAL_STOP, 0.0, 0.0)));
  ASSERT_TRUE(testkit::wait_until([&] { return count_of(group_.log("agv"), "\npaused") > pauses; }, 10s))
      << group_.log("agv") << group_.log("gateway");
  const std::size_t orders = count_of(group_.log("agv"), " update 0");
  ASSERT_TRUE((*goals)->write(make_goal(kRobot, 6, GOAL_DIRECT, 4.0, 6.0)));
  ASSERT_TRUE(paths_.wait_for(
      [](const RobotPath& p) {
        return p.robot_id() == kRobot && p.goal_id() == 6 && p.status() == GOAL_STATUS_REACHED;
      },
      60s))
      << group_.log("agv") << group_.log("gateway");
  agv = group_.log("agv");
  EXPECT_EQ(count_of(agv, " update 0"), orders + 1) << "a new order for the goal elsewhere: " << agv;
  EXPECT_EQ(agv.find("error "), std::string::npos) << agv;
}

// A robot that cannot take orders (switched to MANUAL by its operator) rejects each with its reason;
// the gateway reports them, and after three to one destination sends it no more.
TEST_F(Vda5050Test, OrdersTheRobotRejectsAreReportedWithItsReasonUntilTheGatewayGivesUp) {
  group_.start("planner", {testkit::bin_path("slam-planner"), "--domain", domain(), "--no-share",
                           "--goal-store", group_.dir() + "/goals.json"});
  start_agv(1.0, 1.0, "MANUAL");
  ASSERT_TRUE(wait_state([](const RobotState& s) { return s.status().to_string() == "MANUAL"; }, 60s))
      << group_.log("agv") << group_.log("gateway");
  auto goals = dds::make_writer(*participant_, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();
  ASSERT_TRUE((*goals)->wait_for_readers(30s));
  ASSERT_TRUE((*goals)->write(make_goal(kRobot, 1, GOAL_DIRECT, 1.0, 5.0)));
  ASSERT_TRUE(testkit::wait_until(
      [&] { return group_.log("gateway").find("rejected in a row") != std::string::npos; }, 30s))
      << group_.log("agv") << group_.log("gateway");
  const std::string gateway = group_.log("gateway");
  EXPECT_NE(gateway.find("robot 'SlamTest:agv-1' order slam-"), std::string::npos) << gateway;
  EXPECT_NE(gateway.find("order is not executable due to operating mode"), std::string::npos) << gateway;
  EXPECT_NE(gateway.find("3 orders to (1.00, 5.00) rejected in a row"), std::string::npos) << gateway;
}

TEST_F(Vda5050Test, ARobotWhoseConnectionBreaksIsOffline) {
  start_agv(1.0, 1.0);
  ASSERT_TRUE(wait_state([](const RobotState& s) { return s.presence() == PRESENCE_ONLINE; }, 60s))
      << group_.log("agv") << group_.log("gateway");
  // SIGKILL: no goodbye, so the broker sends the robot's last will, connection CONNECTIONBROKEN.
  group_.stop("agv", SIGKILL);
  ASSERT_TRUE(wait_state([](const RobotState& s) { return s.presence() == PRESENCE_OFFLINE; }, 30s))
      << group_.log("gateway");
  EXPECT_NE(group_.log("gateway").find("robot 'SlamTest:agv-1' offline: last will"), std::string::npos)
      << group_.log("gateway");
}

// The simulator's own VDA robots (--vda-robots: sim-1 speaks VDA 5050 beside a v1 robot in the same
// world): the fleet's order, node by node, to a goal.
TEST_F(Vda5050Test, SimulatedVdaRobotInAMixedFleetReachesASquareGoal) {
  group_.start("planner", {testkit::bin_path("slam-planner"), "--domain", domain(), "--no-share",
                           "--goal-store", group_.dir() + "/goals.json"});
  group_.start("simulator", {testkit::bin_path("slam-simulator"), "--domain", domain(), "--broker", broker_,
                             "--world", "empty", "--robots", "2", "--vda-robots", "1", "--seed", "7"});
  const std::string robot = "slamfleet-sim:sim-1";
  ASSERT_TRUE(states_.wait_for([&](const RobotState& s) { return s.robot_id() == robot; }, 60s))
      << group_.log("simulator") << group_.log("gateway");
  ASSERT_TRUE(states_.wait_for([&](const RobotState& s) { return s.robot_id() == "sim-2"; }, 60s))
      << "the v1 robot beside it";

  auto goals = dds::make_writer(*participant_, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();
  ASSERT_TRUE((*goals)->wait_for_readers(30s));
  NavGoal goal;
  goal.robot_id(robot);
  goal.goal_id(1);
  goal.mode(GOAL_SQUARE);
  Point2 target;
  target.x(3.0);
  target.y(3.0);
  goal.target(target);
  goal.square_size(2.0);
  goal.square_anchor(SQUARE_CORNER);
  ASSERT_TRUE((*goals)->write(goal));
  ASSERT_TRUE(paths_.wait_for(
      [&](const RobotPath& p) { return p.robot_id() == robot && p.status() == GOAL_STATUS_REACHED; }, 120s))
      << group_.log("simulator") << group_.log("gateway") << group_.log("planner");
  EXPECT_EQ(group_.log("simulator").find("ignored"), std::string::npos) << group_.log("simulator");
}

}  // namespace
}  // namespace slam

// Missions end to end on slam-planner: this test plays the mapper (a free room), the gateway (a
// robot that drives to each waypoint it is sent) and the operator (NavMission, NavGoal). A looped
// mission keeps patrolling after the planner is killed (-9) and started again from its goal store,
// and a goal sent afterwards cancels it.
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::Inbox;
using testkit::wait_until;

constexpr const char* kRobot = "patroller";

Point2 pt(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

// 10 m x 6 m of free cells at 0.1 m.
GridSnapshot free_room() {
  GridSnapshot s;
  s.layout_id(1);
  s.version(1);
  s.info().width(100);
  s.info().height(60);
  s.info().resolution(0.1);
  s.info().origin(pt(0, 0));
  s.cells(std::vector<uint8_t>(100 * 60, 1));
  return s;
}

class MissionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    start_planner("planner");
    auto p = dds::Participant::create(domain_.id(), "mission_test");
    ASSERT_TRUE(p) << p.message();
    participant_ = std::move(*p);
    snapshots_ = testkit::make_test_writer(*participant_, dds::kGridSnapshot);
    states_ = testkit::make_test_writer(*participant_, dds::kRobotState);
    goals_ = testkit::make_test_writer(*participant_, dds::kNavGoal);
    waypoint_reader_ = testkit::make_inbox_reader(*participant_, dds::kWaypointCommand, waypoints_);
    mission_reader_ = testkit::make_inbox_reader(*participant_, dds::kNavMission, missions_);
    ASSERT_TRUE(wait_until(
        [&] {
          return snapshots_->matched_readers() > 0 && states_->matched_readers() > 0 &&
                 waypoint_reader_->matched_writers() > 0 && mission_reader_->matched_writers() > 0;
        },
        60s))
        << group_.log("planner");
    snapshots_->write(free_room());
    move_robot(1.0, 1.0);
    robot_ = std::thread([this] { drive(); });
  }

  void TearDown() override {
    stop_ = true;
    if (robot_.joinable()) robot_.join();
    if (HasFailure())
      for (const char* name : {"planner", "planner-restarted"})
        std::cerr << "--- " << name << " log ---\n" << group_.log(name);
  }

  void start_planner(const std::string& name) {
    group_.start(
        name, {testkit::bin_path("slam-planner"), "--domain", std::to_string(domain_.id()),
               "--goals-resend-period-s", "0.3", "--no-share", "--goal-store", group_.dir() + "/goals.json"});
  }

  void move_robot(double x, double y) {
    RobotState s;
    s.robot_id(kRobot);
    s.presence(PRESENCE_ONLINE);
    s.pose().x(x);
    s.pose().y(y);
    states_->write(s);
  }

  // The robot: drives (jumps) to each waypoint it is sent, a little after it was sent.
  void drive() {
    uint64_t done = 0;
    while (!stop_) {
      std::this_thread::sleep_for(150ms);
      const auto cmd = waypoints_.last([](const WaypointCommand& w) { return w.robot_id() == kRobot; });
      if (!cmd || cmd->seq() == done) continue;
      done = cmd->seq();
      move_robot(cmd->waypoint().x(), cmd->waypoint().y());
    }
  }

  // The most laps the planner reported for `mission_id` (0 before any report).
  uint32_t laps(uint64_t mission_id) const {
    uint32_t most = 0;
    for (const NavMission& m : missions_.items())
      if (m.mission_id() == mission_id) most = std::max(most, m.laps());
    return most;
  }

  testkit::DomainLease domain_;
  testkit::ProcessGroup group_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<GridSnapshot>> snapshots_;
  std::unique_ptr<dds::Writer<RobotState>> states_;
  std::unique_ptr<dds::Writer<NavGoal>> goals_;
  Inbox<WaypointCommand> waypoints_;
  Inbox<NavMission> missions_;
  std::unique_ptr<dds::Reader<WaypointCommand>> waypoint_reader_;
  std::unique_ptr<dds::Reader<NavMission>> mission_reader_;
  std::atomic<bool> stop_{false};
  std::thread robot_;
};

TEST_F(MissionTest, ALoopedMissionKeepsPatrollingAfterAPlannerRestartAndAGoalCancelsIt) {
  constexpr uint64_t kMission = 77;
  {
    // Sent by a short-lived client (like slamctl): after the restart only the goal store has it.
    auto sender = testkit::make_test_writer(*participant_, dds::kNavMission);
    NavMission m;
    m.robot_id(kRobot);
    m.mission_id(kMission);
    m.waypoints({pt(2.0, 1.0), pt(8.0, 1.0), pt(8.0, 5.0)});
    m.loop(true);
    m.status(MISSION_ACTIVE);
    ASSERT_TRUE(wait_until([&] { return sender->matched_readers() > 1; }, 30s));
    sender->write(m);
    ASSERT_TRUE(wait_until([&] { return laps(kMission) >= 2; }, 90s)) << "the patrol never looped twice";
    ASSERT_TRUE(sender->wait_for_acknowledgments(10s));
  }

  group_.stop("planner", SIGKILL);
  const uint32_t before = laps(kMission);
  std::this_thread::sleep_for(1s);  // whatever the killed planner sent has arrived
  start_planner("planner-restarted");
  EXPECT_TRUE(wait_until([&] { return laps(kMission) >= before + 2; }, 90s))
      << "laps before the restart: " << before << ", now: " << laps(kMission);
  EXPECT_NE(group_.log("planner-restarted").find("1 mission(s) resumed"), std::string::npos);
  // Still the same patrol: every reported waypoint index is one of the three.
  for (const NavMission& m : missions_.items()) {
    if (m.mission_id() == kMission) {
      EXPECT_LT(m.current(), 3u);
    }
  }

  // A goal sent later cancels the mission, and the planner says so on the mission's topic.
  NavGoal stop;
  stop.robot_id(kRobot);
  stop.goal_id(78);
  stop.mode(GOAL_STOP);
  goals_->write(stop);
  EXPECT_TRUE(wait_until(
      [&] {
        const auto last = missions_.last([](const NavMission& m) { return m.mission_id() == kMission; });
        return last && last->status() == MISSION_CANCELLED;
      },
      30s));
}

}  // namespace
}  // namespace slam

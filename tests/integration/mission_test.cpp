// Missions end to end on slam-planner: this test plays the mapper (a free room), the gateway (a
// robot that drives to each waypoint it is sent) and the operator (NavMission, NavGoal). A looped
// mission keeps patrolling after the planner is killed (-9) and started again from its goal store,
// and a goal sent afterwards cancels it; with two planners sharing the robot, it keeps patrolling
// while either of them is killed.
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <limits>
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
    auto p = dds::Participant::create(domain_.id(), "mission_test");
    ASSERT_TRUE(p) << p.message();
    participant_ = std::move(*p);
    snapshots_ = testkit::make_test_writer(*participant_, dds::kGridSnapshot);
    states_ = testkit::make_test_writer(*participant_, dds::kRobotState);
    goals_ = testkit::make_test_writer(*participant_, dds::kNavGoal);
    waypoint_reader_ = testkit::make_inbox_reader(*participant_, dds::kWaypointCommand, waypoints_);
    mission_reader_ = testkit::make_inbox_reader(*participant_, dds::kNavMission, missions_);
    snapshots_->write(free_room());
    move_robot(1.0, 1.0);
    robot_ = std::thread([this] { drive(); });
  }

  // Waits for the planners started to match the test's topics.
  void connect(int planners) {
    ASSERT_TRUE(wait_until(
        [&] {
          return snapshots_->matched_readers() >= planners && states_->matched_readers() >= planners &&
                 waypoint_reader_->matched_writers() >= planners &&
                 mission_reader_->matched_writers() >= planners;
        },
        60s));
  }

  // Sends the patrol from a short-lived client (like slamctl, gone before any restart: then only
  // the goal stores have it) and waits until the robot drove it twice.
  void send_patrol(uint64_t mission_id, int planners) {
    auto sender = testkit::make_test_writer(*participant_, dds::kNavMission);
    NavMission m;
    m.robot_id(kRobot);
    m.mission_id(mission_id);
    m.waypoints({pt(2.0, 1.0), pt(8.0, 1.0), pt(8.0, 5.0)});
    m.loop(true);
    m.status(MISSION_ACTIVE);
    // Every planner and the test's own reader.
    ASSERT_TRUE(wait_until([&] { return sender->matched_readers() > planners; }, 30s));
    sender->write(m);
    ASSERT_TRUE(wait_until([&] { return laps(mission_id) >= 2; }, 90s)) << "the patrol never looped twice";
    ASSERT_TRUE(sender->wait_for_acknowledgments(10s));
  }

  void TearDown() override {
    stop_ = true;
    if (robot_.joinable()) robot_.join();
    if (HasFailure())
      for (const char* name : {"planner", "planner-restarted", "planner-a", "planner-b", "planner-a2"})
        std::cerr << "--- " << name << " log ---\n" << group_.log(name);
  }

  // A lone planner keeping its goals in `store`, or (`share`) one of several sharing the robot.
  void start_planner(const std::string& name, const std::string& store, bool share = false) {
    std::vector<std::string> argv{testkit::bin_path("slam-planner"), "--domain", std::to_string(domain_.id()),
                                  "--goals-resend-period-s",         "0.3",      "--goal-store",
                                  group_.dir() + "/" + store};
    if (!share) argv.push_back("--no-share");
    group_.start(name, argv);
  }

  void move_robot(double x, double y) {
    RobotState s;
    s.robot_id(kRobot);
    s.presence(PRESENCE_ONLINE);
    s.battery(-1.0f);  // unknown, as a v1 robot's: 0 would be an empty battery (sent home)
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

  // The most laps the planners reported for `mission_id` (0 before any report).
  uint32_t laps(uint64_t mission_id) const {
    uint32_t most = 0;
    for (const NavMission& m : missions_.items())
      if (m.mission_id() == mission_id) most = std::max(most, m.laps());
    return most;
  }

  // The fewest laps reported for `mission_id` from the `from`-th report received on.
  uint32_t fewest_laps_since(size_t from, uint64_t mission_id) const {
    const auto items = missions_.items();
    uint32_t fewest = std::numeric_limits<uint32_t>::max();
    for (size_t i = from; i < items.size(); ++i)
      if (items[i].mission_id() == mission_id) fewest = std::min(fewest, items[i].laps());
    return fewest;
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
  start_planner("planner", "goals.json");
  connect(1);
  send_patrol(kMission, 1);

  group_.stop("planner", SIGKILL);
  const uint32_t before = laps(kMission);
  std::this_thread::sleep_for(1s);  // whatever the killed planner sent has arrived
  start_planner("planner-restarted", "goals.json");
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

TEST_F(MissionTest, WithTwoPlannersThePatrolContinuesWhicheverOfThemIsKilled) {
  constexpr uint64_t kMission = 91;
  start_planner("planner-a", "goals-a.json", true);
  start_planner("planner-b", "goals-b.json", true);
  connect(2);
  send_patrol(kMission, 2);
  // One of the two drives the robot; each is killed in turn (the first restarted in between), so
  // the owner is killed once: the survivor continues from the waypoint it learnt from the owner.
  // The survivor continues the patrol where it was, not from its start.
  group_.stop("planner-a", SIGKILL);
  uint32_t before = laps(kMission);
  size_t from = missions_.size();
  EXPECT_TRUE(wait_until([&] { return laps(kMission) >= before + 2; }, 90s))
      << "after planner-a was killed: " << laps(kMission) << " laps, " << before << " before";
  EXPECT_GE(fewest_laps_since(from, kMission), before);
  start_planner("planner-a2", "goals-a.json", true);
  std::this_thread::sleep_for(5s);  // past its warm-up: it shares the robot again
  group_.stop("planner-b", SIGKILL);
  before = laps(kMission);
  from = missions_.size();
  EXPECT_TRUE(wait_until([&] { return laps(kMission) >= before + 2; }, 90s))
      << "after planner-b was killed: " << laps(kMission) << " laps, " << before << " before";
  EXPECT_GE(fewest_laps_since(from, kMission), before);
}

}  // namespace
}  // namespace slam

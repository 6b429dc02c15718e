// Fleet coordination end to end: mosquitto, gateway, mapper, planner and the simulator in a room
// split by a wall with one 0.7 m door. Two robots stand on one line through the door, facing each
// other, and are sent past each other through it; their planned paths overlap up to and through the
// door, so robots that ignore each other meet nose to nose. With coordination (the planner's default) both
// must reach their goals and the simulator's robot_contacts counter must stay 0.
// COORDINATION_TEST_MODE=off runs the same scene with --coordination off (the test then fails:
// that is how the scene was checked to be a real test).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <thread>

#include "common/fastdds/fast_topics.hpp"
#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::bin_path;
using testkit::wait_until;

constexpr double kSpeed = 2.0;  // simulated seconds per wall-clock second
constexpr auto kBudget = 120s;  // wall clock, from the goals to both arrivals

// 10 m x 6 m; the wall at x = 5 m leaves a door at y 2.65..3.35 m (Java world text, centimetres).
constexpr const char* kWorld = "1000:600 500,0:500,265 500,335:500,600";

struct Robot {
  const char* id;
  double x, y, theta;  // spawn pose
  double goal_x, goal_y;
  uint64_t goal_id;
};
// Each goal lies off the other robot's start, so the first to arrive does not park in the way.
constexpr Robot kWest{"west", 1.5, 3.0, 0.0, 7.5, 4.2, 101};
constexpr Robot kEast{"east", 8.5, 3.0, std::numbers::pi, 2.5, 1.8, 102};

class Observer {
 public:
  void on_state(const RobotState& s) {
    std::lock_guard lock(mutex_);
    seen_[s.robot_id().to_string()] = true;
  }
  void on_path(const RobotPath& p) {
    std::lock_guard lock(mutex_);
    paths_[p.robot_id().to_string()] = p;
  }
  void on_heartbeat(const Heartbeat& h) {
    if (h.service().to_string() != "simulator") return;
    std::lock_guard lock(mutex_);
    for (const Counter& c : h.counters())
      if (c.name().to_string() == "robot_contacts") contacts_ = c.value();
  }
  bool seen(const std::string& id) const {
    std::lock_guard lock(mutex_);
    return seen_.count(id) > 0;
  }
  bool reached(const Robot& r) const {
    std::lock_guard lock(mutex_);
    const auto it = paths_.find(r.id);
    return it != paths_.end() && it->second.goal_id() == r.goal_id &&
           it->second.status() == GOAL_STATUS_REACHED;
  }
  std::optional<int64_t> contacts() const {
    std::lock_guard lock(mutex_);
    return contacts_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, bool> seen_;
  std::map<std::string, RobotPath> paths_;
  std::optional<int64_t> contacts_;
};

TEST(CoordinationTest, TwoRobotsThroughOneDoorInOppositeDirectionsArriveWithoutContact) {
  const char* env_mode = std::getenv("COORDINATION_TEST_MODE");
  const std::string mode = env_mode != nullptr ? env_mode : "on";
  testkit::DomainLease lease;
  testkit::ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  const std::string world_file = group.dir() + "/door.txt";
  std::ofstream(world_file) << kWorld << "\n";
  const int port = group.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(port);
  group.start("gateway", {bin_path("slam-gateway"), "--domain", domain, "--broker", broker, "--no-share"});
  group.start("mapper", {bin_path("slam-mapper"), "--domain", domain, "--store", group.dir() + "/map.db"});
  // Unknown space is allowed: the goals start before the far room is mapped.
  group.start("planner", {bin_path("slam-planner"), "--domain", domain, "--goal-store", "", "--no-share",
                          "--planner-unknown", "allowed", "--coordination", mode});
  group.start("simulator",
              {bin_path("slam-simulator"), "--domain", domain, "--broker", broker, "--world", world_file,
               "--robots", "0", "--speed", std::to_string(kSpeed), "--drift", "0", "--seed", "3"});

  auto participant = dds::Participant::create(lease.id(), "coordination_test");
  ASSERT_TRUE(participant) << participant.message();
  Observer seen;
  auto states = dds::make_reader(**participant, dds::kRobotState,
                                 [&](const RobotState& s, const auto&) { seen.on_state(s); });
  ASSERT_TRUE(states) << states.message();
  auto paths = dds::make_reader(**participant, dds::kRobotPath,
                                [&](const RobotPath& p, const auto&) { seen.on_path(p); });
  ASSERT_TRUE(paths) << paths.message();
  auto heartbeats = dds::make_reader(**participant, dds::kHeartbeat,
                                     [&](const Heartbeat& h, const auto&) { seen.on_heartbeat(h); });
  ASSERT_TRUE(heartbeats) << heartbeats.message();

  auto control = dds::make_writer(**participant, dds::kSimControl);
  ASSERT_TRUE(control) << control.message();
  ASSERT_TRUE((*control)->wait_for_readers(30s));
  // Sent again (same ids: the simulator applies each once) until both robots report: a command
  // written while discovery still settles may be missed.
  const auto spawn_both = [&] {
    uint64_t command_id = 1;
    for (const Robot& r : {kWest, kEast}) {
      SimControl spawn;
      spawn.command_id(command_id++);
      spawn.kind(SIM_SPAWN);
      Pose2 pose;
      pose.x(r.x);
      pose.y(r.y);
      pose.theta(r.theta);
      spawn.poses().push_back(pose);
      spawn.robot_id(r.id);
      (*control)->write(spawn);
    }
    return wait_until([&] { return seen.seen(kWest.id) && seen.seen(kEast.id); }, 3s);
  };
  ASSERT_TRUE(wait_until(spawn_both, 60s, 0ms)) << "the robots' states did not reach DDS";
  // A moment of scans first, so the wall and the door are in the map when the planner plans.
  std::this_thread::sleep_for(2s);

  auto goals = dds::make_writer(**participant, dds::kNavGoal);
  ASSERT_TRUE(goals) << goals.message();
  ASSERT_TRUE((*goals)->wait_for_readers(30s));
  for (const Robot& r : {kWest, kEast}) {
    NavGoal goal;
    goal.robot_id(r.id);
    goal.goal_id(r.goal_id);
    goal.mode(GOAL_PLANNED);
    Point2 target;
    target.x(r.goal_x);
    target.y(r.goal_y);
    goal.target(target);
    ASSERT_TRUE((*goals)->write(goal));
  }

  const bool arrived = wait_until([&] { return seen.reached(kWest) && seen.reached(kEast); }, kBudget);
  // The simulator's heartbeat (once a second) carries the contacts up to now.
  std::this_thread::sleep_for(1500ms);
  const auto contacts = seen.contacts();
  std::printf("coordination %s: west %s, east %s, robot_contacts %lld\n", mode.c_str(),
              seen.reached(kWest) ? "arrived" : "did not arrive",
              seen.reached(kEast) ? "arrived" : "did not arrive",
              contacts ? static_cast<long long>(*contacts) : -1LL);
  EXPECT_TRUE(arrived) << "west reached: " << seen.reached(kWest)
                       << ", east reached: " << seen.reached(kEast);
  ASSERT_TRUE(contacts.has_value()) << "no simulator heartbeat with robot_contacts";
  EXPECT_EQ(*contacts, 0);
}

}  // namespace
}  // namespace slam

// Targets in unexplored space, end to end: mosquitto + slam-gateway + slam-mapper + slam-planner and a
// legacy (v1) robot on paho. The robot reports a wall and is sent to a point behind it, in space
// nobody has seen: it is steered around the wall, not refused. A goal inside a room whose walls are
// all known fails, and the robot's path says why.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "fastdds_inbox.hpp"
#include "process_group.hpp"
#include "system_fixture.hpp"

namespace slam::system_test {
namespace {

using testkit::bin_path;
using testkit::wait_until;

constexpr const char* kRobot = "legacy7";

// A closed room x -2.98..-1.98 m, y 2.02..2.98 m (cells 140..160 x 240..259 at 5 cm from -10 m): its
// inside is never seen, so the goal at its centre lies in unexplored space enclosed by known walls.
// Each wall is reported from a point in front of it, so no ray crosses another wall.
struct Room {
  static constexpr Vec kCentre{-2.48, 2.5};
  struct Face {
    Vec from;
    std::vector<Vec> points;
  };
  static std::vector<Face> faces() {
    std::vector<Face> out(4);
    out[0].from = {-3.5, 2.5};  // west wall
    out[1].from = {-1.5, 2.5};  // east wall
    out[2].from = {-2.5, 1.5};  // south wall
    out[3].from = {-2.5, 3.5};  // north wall
    for (int cm = 202; cm <= 297; cm += 5) {
      out[0].points.push_back({-2.98, cm / 100.0});
      out[1].points.push_back({-1.98, cm / 100.0});
    }
    for (int cm = -298; cm <= -198; cm += 5) {
      out[2].points.push_back({cm / 100.0, 2.02});
      out[3].points.push_back({cm / 100.0, 2.97});
    }
    return out;
  }
};

class UnknownSpaceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string domain = std::to_string(domain_.id());
    group_.start("gateway", {bin_path("slam-gateway"), "--domain", domain, "--broker",
                             "tcp://127.0.0.1:" + std::to_string(port_)});
    // SLAM off: the robot's reports are the map frame, so the test can judge waypoints against the wall.
    group_.start("mapper", {bin_path("slam-mapper"), "--domain", domain, "--store", group_.dir() + "/map.db",
                            "--slam", "off"});
    // The planner's defaults: unexplored space allowed.
    group_.start("planner", {bin_path("slam-planner"), "--domain", domain, "--no-share", "--goal-store",
                             group_.dir() + "/goals.json"});
    participant_ = take(dds::Participant::create(domain_.id(), "unknown-space-test"));
    path_reader_ = testkit::make_inbox_reader(*participant_, dds::kRobotPath, paths_);
    for (const char* s : {"gateway", "mapper", "planner"}) {
      ASSERT_TRUE(wait_until([&] { return probe_.heartbeat(s).has_value(); }, 30s))
          << s << " never sent a heartbeat\n"
          << group_.log(s);
    }
  }

  void TearDown() override {
    if (HasFailure()) std::cerr << group_.log("planner") << group_.log("gateway") << group_.log("mapper");
  }

  // The robot reports `adv` until the published map satisfies `mapped`.
  void report_until(PahoRobot& robot, const std::string& adv, const std::function<bool(const Map&)>& mapped,
                    const std::string& what) {
    robot.set_adv(adv);
    ASSERT_TRUE(wait_until(
        [&] {
          const auto m = probe_.map();
          return m && mapped(*m);
        },
        60s, 50ms))
        << what << " never reached the map";
  }

  // The robot's newest RobotPath for goal `goal_id` whose status is `status` (and, with
  // `with_waypoints`, that holds a path).
  std::optional<RobotPath> path_with(uint64_t goal_id, GoalStatus status, bool with_waypoints = false) {
    return paths_.wait_for(
        [&](const RobotPath& p) {
          return p.robot_id() == kRobot && p.goal_id() == goal_id && p.status() == status &&
                 (!with_waypoints || !p.waypoints().empty());
        },
        30s);
  }

  testkit::DomainLease domain_;
  testkit::ProcessGroup group_;
  int port_ = group_.start_mosquitto();
  Probe probe_{domain_.id()};
  std::unique_ptr<dds::Participant> participant_;
  testkit::Inbox<RobotPath> paths_;
  std::unique_ptr<dds::Reader<RobotPath>> path_reader_;
};

TEST_F(UnknownSpaceTest, AV1RobotSentBehindItsReportedWallIsSteeredAroundIt) {
  PahoRobot robot(port_, kRobot, v1_adv(Scene::kStart, Scene::wall()));
  // Only the wall and the rays to it are known: the goal behind it is unexplored.
  ASSERT_NO_FATAL_FAILURE(report_until(
      robot, v1_adv(Scene::kStart, Scene::wall()),
      [](const Map& m) { return m.state(1.52, 0.03) == CELL_OCCUPIED && m.state(1.0, 0.0) == CELL_FREE; },
      "the reported wall"));
  const auto map = probe_.map();
  ASSERT_EQ(map->state(Scene::kGoal), CELL_UNKNOWN) << "the goal must lie in unexplored space";
  // The planner may still hold an older map (a just-joined reader's first snapshot is the stored one);
  // a goal planned on it would go straight through the wall before the re-plan.
  ASSERT_TRUE(wait_until(
      [&] { return probe_.counter("planner", 0, "map_version") >= static_cast<int64_t>(map->version); }, 30s))
      << "the planner never caught up with map version " << map->version;

  const auto since = Clock::now();
  ASSERT_TRUE(probe_.set_goal(kRobot, GOAL_PLANNED, Scene::kGoal));
  // Drive: the robot reports itself at each waypoint it is sent (position only) until the goal.
  std::vector<Vec> route{Scene::kStart};
  ASSERT_TRUE(wait_until(
      [&] {
        const auto commands = robot.commands(since);
        if (commands.empty()) return false;
        const auto w = v1_cmd(commands.back().second);
        if (w && distance(*w, route.back()) > 0.015) {
          route.push_back(*w);
          robot.set_adv(v1_adv(*w));
        }
        return distance(route.back(), Scene::kGoal) < 0.015;
      },
      60s, 50ms))
      << "the robot never got to the goal; route so far has " << route.size() << " points";
  ASSERT_GE(route.size(), 3u) << "a route around the wall bends at least once";
  for (size_t i = 1; i < route.size(); ++i) {
    EXPECT_GT(segment_distance(route[i - 1], route[i], Scene::kWallA, Scene::kWallB), 0.05)
        << "segment (" << route[i - 1].x << ", " << route[i - 1].y << ") -> (" << route[i].x << ", "
        << route[i].y << ") crosses or grazes the reported wall";
  }
  std::cout << "[ route  ]";
  for (const Vec& p : route) std::cout << " (" << p.x << ", " << p.y << ")";
  std::cout << "\n";
  EXPECT_TRUE(path_with(101, GOAL_STATUS_REACHED)) << "the goal was never reported reached";
}

TEST_F(UnknownSpaceTest, AGoalInsideAClosedKnownRoomFailsWithTheReason) {
  PahoRobot robot(port_, kRobot, v1_adv(Scene::kStart));
  for (const Room::Face& face : Room::faces()) {
    ASSERT_NO_FATAL_FAILURE(report_until(
        robot, v1_adv(face.from, face.points),
        [&face](const Map& m) {
          for (const Vec& p : face.points)
            if (m.state(p) != CELL_OCCUPIED) return false;
          return true;
        },
        "a wall of the room"));
  }
  robot.set_adv(v1_adv(Scene::kStart));
  const auto map = probe_.map();
  ASSERT_EQ(map->state(Room::kCentre), CELL_UNKNOWN) << "the room's inside must be unexplored";

  ASSERT_TRUE(probe_.set_goal(kRobot, GOAL_PLANNED, Room::kCentre));
  const auto failed = path_with(101, GOAL_STATUS_FAILED);
  ASSERT_TRUE(failed) << "the goal inside the closed room never failed";
  const std::string reason = failed->reason().to_string();
  EXPECT_NE(reason.find("NO_PATH"), std::string::npos) << reason;
  EXPECT_NE(reason.find("enclosed by known walls"), std::string::npos) << reason;

  // The same robot is still sent into unexplored space outside the room.
  ASSERT_TRUE(probe_.set_goal(kRobot, GOAL_PLANNED, Vec{3.0, -3.0}));
  EXPECT_TRUE(path_with(102, GOAL_STATUS_ACTIVE, true)) << "a goal in open unexplored space got no path";
}

}  // namespace
}  // namespace slam::system_test

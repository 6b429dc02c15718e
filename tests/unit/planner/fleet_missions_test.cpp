// FleetMissions: a mission drives a robot through its waypoints on a real Fleet (a patrol wraps and
// keeps going), goals and missions replace each other by their senders' order, a planner that does
// not own the robot follows the owner's progress, and a restart resumes from the store.
#include "planner/core/fleet_missions.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "grid_builder.hpp"

namespace slam::planner {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

PlanningGrid open_room() {
  return test::uniform_grid(10, 4, kCellFree);
}

ReceivedMission patrol(int64_t sent_ns, uint64_t id = 9) {
  return ReceivedMission{"r", Mission{id, {{7.5, 0.5}, {1.5, 2.5}}, true}, {}, sent_ns};
}

// Drives "r" onto its current waypoint and lets the fleet and the missions see it.
void arrive(Fleet& fleet, FleetMissions& missions, const PlanningGrid& g, int64_t now) {
  fleet.tick(g, now);
  const GoalTracker* t = fleet.tracker("r");
  ASSERT_TRUE(t->current_waypoint());
  fleet.observe("r", t->waypoints().back());
  missions.step(fleet);
}

TEST(FleetMissions, APatrolVisitsItsWaypointsInOrderAndWraps) {
  const PlanningGrid g = open_room();
  Fleet fleet({});
  auto store = GoalStore::open("");
  FleetMissions missions;
  fleet.observe("r", {0.5, 0.5});
  fleet.grid_changed(g, std::nullopt);
  auto receipt = missions.receive(patrol(100), fleet, *store);
  ASSERT_TRUE(receipt) << receipt.message();
  EXPECT_EQ(*receipt, FleetMissions::Receipt::Started);
  EXPECT_EQ(fleet.tracker("r")->goal().goal_id, 9u);
  EXPECT_EQ(fleet.tracker("r")->target(), (Vec2{7.5, 0.5}));

  arrive(fleet, missions, g, 0);
  EXPECT_EQ(fleet.tracker("r")->target(), (Vec2{1.5, 2.5}));
  arrive(fleet, missions, g, kSecond);
  EXPECT_EQ(fleet.tracker("r")->target(), (Vec2{7.5, 0.5}));
  EXPECT_EQ(fleet.tracker("r")->status(), GoalStatus::Active);
  const auto* running = missions.runner().find("r");
  EXPECT_EQ(running->progress.current, 0u);
  EXPECT_EQ(running->progress.laps, 1u);

  std::vector<std::string> publish;
  missions.take_changed(fleet, *store, publish);
  EXPECT_EQ(publish, std::vector<std::string>{"r"});
  ASSERT_EQ(store->record().missions.count("r"), 1u);
  EXPECT_EQ(store->record().missions.at("r").progress.laps, 1u);
  EXPECT_EQ(store->record().missions.at("r").sent_ns, 100);
}

TEST(FleetMissions, AnUnreachableWaypointIsSkipped) {
  const PlanningGrid g = test::grid_from_art({
      "......###.",
      "......#.#.",
      "......###.",
  });
  Fleet fleet({});
  auto store = GoalStore::open("");
  FleetMissions missions;
  fleet.observe("r", {0.5, 0.5});
  fleet.grid_changed(g, std::nullopt);
  ASSERT_TRUE(missions.receive(ReceivedMission{"r", Mission{4, {{7.5, 1.5}, {2.5, 2.5}}, true}, {}, 1}, fleet,
                               *store));
  fleet.tick(g, 0);
  ASSERT_EQ(fleet.tracker("r")->status(), GoalStatus::Failed);
  EXPECT_EQ(missions.step(fleet), std::vector<std::string>{"r"});
  EXPECT_EQ(fleet.tracker("r")->target(), (Vec2{2.5, 2.5}));
  EXPECT_EQ(fleet.tracker("r")->status(), GoalStatus::Active);
  EXPECT_NE(missions.runner().find("r")->progress.reason.find("waypoint 0 skipped"), std::string::npos);
}

TEST(FleetMissions, GoalsAndMissionsReplaceEachOtherInTheOrderTheyWereSent) {
  Fleet fleet({});
  auto store = GoalStore::open("");
  FleetMissions missions;
  fleet.observe("r", {0.5, 0.5});
  store->put(StoredGoal{"r", Goal{1, GoalMode::Stop, {}, 0, {}}, 200, false});
  // Sent before the goal the store keeps: a replay.
  EXPECT_EQ(*missions.receive(patrol(150), fleet, *store), FleetMissions::Receipt::Replayed);
  EXPECT_FALSE(missions.runner().active("r"));
  EXPECT_EQ(*missions.receive(patrol(300), fleet, *store), FleetMissions::Receipt::Started);
  std::vector<std::string> publish;
  missions.take_changed(fleet, *store, publish);
  EXPECT_TRUE(store->record().goals.at("r").finished) << "the mission replaced the goal";

  // A later goal (here exploration for the whole fleet) cancels the mission.
  missions.goal_accepted(kAllRobots);
  store->put(StoredGoal{kAllRobots, Goal{2, GoalMode::Explore, {}, 0, {}}, 400, false});
  EXPECT_EQ(missions.runner().find("r")->progress.status, MissionStatus::Cancelled);
  missions.take_changed(fleet, *store, publish);
  EXPECT_EQ(store->record().missions.at("r").progress.status, MissionStatus::Cancelled);
  EXPECT_TRUE(missions_to_resume(store->record()).empty());
  // The cancelled mission's own report does not start it again.
  auto ended = patrol(500);
  ended.progress.status = MissionStatus::Cancelled;
  EXPECT_EQ(*missions.receive(ended, fleet, *store), FleetMissions::Receipt::Ignored);
}

TEST(FleetMissions, APlannerNotOwningTheRobotFollowsTheOwnersProgress) {
  const PlanningGrid g = open_room();
  Fleet fleet({});
  auto store = GoalStore::open("");
  FleetMissions missions;
  fleet.observe("r", {0.5, 0.5});
  fleet.update_ownership([](const std::string&) { return false; });
  ASSERT_TRUE(missions.receive(patrol(100), fleet, *store));
  // The robot reaches its waypoint under the other planner: nothing moves on here...
  fleet.observe("r", {7.5, 0.5});
  EXPECT_TRUE(missions.step(fleet).empty());
  EXPECT_EQ(missions.runner().find("r")->progress.current, 0u);
  // ...until the owner reports it.
  auto report = patrol(900);
  report.progress = MissionProgress{1, 2, MissionStatus::Active, ""};
  EXPECT_EQ(*missions.receive(report, fleet, *store), FleetMissions::Receipt::Adopted);
  EXPECT_EQ(fleet.tracker("r")->target(), (Vec2{1.5, 2.5}));
  std::vector<std::string> publish;
  missions.take_changed(fleet, *store, publish);
  EXPECT_TRUE(publish.empty()) << "only the owner reports";
  EXPECT_EQ(store->record().missions.at("r").progress.laps, 2u);
  EXPECT_EQ(store->record().missions.at("r").sent_ns, 100) << "ordered by the sender, not the reporter";

  // Taken over: this planner plans the current leg and moves the mission on itself.
  fleet.update_ownership([](const std::string&) { return true; });
  arrive(fleet, missions, g, kSecond);
  EXPECT_EQ(missions.runner().find("r")->progress.laps, 3u);
  EXPECT_EQ(fleet.tracker("r")->target(), (Vec2{7.5, 0.5}));
}

TEST(FleetMissions, ARestartedPlannerResumesTheMissionWhereItWas) {
  const PlanningGrid g = open_room();
  auto store = GoalStore::open("");
  {
    Fleet fleet({});
    FleetMissions missions;
    fleet.observe("r", {0.5, 0.5});
    fleet.grid_changed(g, std::nullopt);
    ASSERT_TRUE(missions.receive(patrol(100), fleet, *store));
    arrive(fleet, missions, g, 0);
    std::vector<std::string> publish;
    missions.take_changed(fleet, *store, publish);
  }
  auto reopened = parse_goal_record(format_goal_record(store->record()));
  ASSERT_TRUE(reopened) << reopened.message();
  Fleet fleet({});
  FleetMissions missions;
  EXPECT_EQ(missions.resume(*reopened, fleet), 1u);
  fleet.observe("r", {7.5, 0.5});
  EXPECT_EQ(fleet.tracker("r")->goal().goal_id, 9u);
  EXPECT_EQ(fleet.tracker("r")->target(), (Vec2{1.5, 2.5}));
  EXPECT_EQ(missions.runner().find("r")->progress.current, 1u);
  // The sender's sample replayed from a DDS cache is the running mission: nothing restarts.
  EXPECT_EQ(*missions.receive(patrol(100), fleet, *store), FleetMissions::Receipt::Ignored);
  EXPECT_EQ(missions.runner().find("r")->progress.current, 1u);
}

TEST(FleetMissions, InvalidMissionsAreRefused) {
  Fleet fleet({});
  auto store = GoalStore::open("");
  FleetMissions missions;
  auto all = patrol(1);
  all.robot_id = kAllRobots;
  EXPECT_FALSE(missions.receive(all, fleet, *store));
  auto empty = patrol(1);
  empty.mission.waypoints.clear();
  EXPECT_FALSE(missions.receive(empty, fleet, *store));
  EXPECT_EQ(fleet.pending_goal("r"), nullptr);
}

}  // namespace
}  // namespace slam::planner

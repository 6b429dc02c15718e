// GoalStore: the goal file round-trips, bad files are refused with the field named, goals resume
// in the order they were given, and replays from DDS caches are recognised as stale.
#include "planner/core/goal_store.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "planner/core/fleet.hpp"
#include "temp_dir.hpp"

namespace slam::planner {
namespace {

namespace fs = std::filesystem;

GoalRecord sample_record() {
  GoalRecord r;
  r.goals["r1"] =
      StoredGoal{"r1", Goal{11, GoalMode::Planned, {2.5, -1.25}, 0.0, SquareAnchor::Corner}, 300, false};
  r.goals["r2"] = StoredGoal{"r2", Goal{12, GoalMode::Square, {1, 1}, 2.0, SquareAnchor::Centred}, 100, true};
  r.goals["*"] = StoredGoal{"*", Goal{13, GoalMode::Explore, {}, 0.0, SquareAnchor::Corner}, 200, false};
  r.homes["r1"] = Vec2{0.5, 0.75};
  return r;
}

void expect_same(const StoredGoal& a, const StoredGoal& b) {
  EXPECT_EQ(a.robot_id, b.robot_id);
  EXPECT_EQ(a.goal.goal_id, b.goal.goal_id);
  EXPECT_EQ(a.goal.mode, b.goal.mode);
  EXPECT_EQ(a.goal.target, b.goal.target);
  EXPECT_EQ(a.goal.square_size, b.goal.square_size);
  EXPECT_EQ(a.goal.square_anchor, b.goal.square_anchor);
  EXPECT_EQ(a.sent_ns, b.sent_ns);
  EXPECT_EQ(a.finished, b.finished);
}

TEST(GoalRecord, RoundTripsThroughItsText) {
  const GoalRecord original = sample_record();
  auto parsed = parse_goal_record(format_goal_record(original));
  ASSERT_TRUE(parsed) << parsed.message();
  ASSERT_EQ(parsed->goals.size(), 3u);
  for (const auto& [id, g] : original.goals) expect_same(parsed->goals.at(id), g);
  EXPECT_EQ(parsed->homes, original.homes);
}

TEST(GoalRecord, BadFilesNameWhatIsWrong) {
  const auto error_of = [](const std::string& text) {
    auto r = parse_goal_record(text);
    return r ? std::string("accepted") : r.message();
  };
  const std::string head = R"({"format": "slam-planner-goals", "version": 1, )";
  EXPECT_EQ(error_of("{"), "not valid JSON");
  EXPECT_EQ(error_of("[]"), "must be a JSON object");
  EXPECT_NE(error_of(R"({"format": "x", "version": 1})").find("\"format\""), std::string::npos);
  EXPECT_NE(error_of(R"({"format": "slam-planner-goals", "version": 2})").find("\"version\" must be 1"),
            std::string::npos);
  EXPECT_NE(error_of(head + R"("goals": [{"robot_id": "a"}]})").find("goals[0] has no \"goal_id\""),
            std::string::npos);
  const std::string goal =
      R"({"robot_id": "a", "goal_id": 1, "mode": "planned", "target": [1, 2], "sent_ns": 5, "finished": false})";
  EXPECT_EQ(error_of(head + R"("goals": [)" + goal + "]}"), "accepted");
  std::string bad_mode = goal;
  bad_mode.replace(bad_mode.find("planned"), 7, "flying");
  EXPECT_NE(error_of(head + R"("goals": [)" + bad_mode + "]}").find("goals[0].mode must be one of idle"),
            std::string::npos);
  std::string bad_target = goal;
  bad_target.replace(bad_target.find("[1, 2]"), 6, "[1]");
  EXPECT_NE(error_of(head + R"("goals": [)" + bad_target + "]}").find("goals[0].target must be [x, y]"),
            std::string::npos);
  EXPECT_NE(error_of(head + R"("goals": [)" + goal + "," + goal + "]}").find("a second goal for robot 'a'"),
            std::string::npos);
  std::string long_id = goal;
  long_id.replace(long_id.find("\"a\""), 3, "\"" + std::string(65, 'x') + "\"");
  EXPECT_NE(error_of(head + R"("goals": [)" + long_id + "]}").find("1 to 64 characters"), std::string::npos);
  std::string bad_square = goal;
  bad_square.replace(bad_square.find("planned"), 7, "square");
  bad_square.insert(1, R"("square_size": -1, )");
  EXPECT_NE(error_of(head + R"("goals": [)" + bad_square + "]}").find("goals[0]: "), std::string::npos);
  EXPECT_NE(error_of(head + R"("homes": {"a": "here"}})").find("homes.a must be [x, y]"), std::string::npos);
}

TEST(GoalRecord, ResumesUnfinishedGoalsOldestFirstWithFleetGoalsBeforeTheirRobots) {
  GoalRecord r = sample_record();
  r.goals["r3"] = StoredGoal{"r3", Goal{13, GoalMode::Explore, {}, 0.0, SquareAnchor::Corner}, 200, false};
  const auto order = goals_to_resume(r);
  ASSERT_EQ(order.size(), 3u);  // r2 is finished
  EXPECT_EQ(order[0].robot_id, "*");
  EXPECT_EQ(order[1].robot_id, "r3");
  EXPECT_EQ(order[2].robot_id, "r1");
}

TEST(GoalStore, KeepsGoalsAndHomesAcrossReopening) {
  testkit::TempDir dir("goal-store");
  const std::string path = (dir.path() / "sub" / "goals.json").string();
  auto store = GoalStore::open(path);
  ASSERT_TRUE(store) << store.message();
  EXPECT_TRUE(store->record().goals.empty());
  EXPECT_FALSE(store->dirty());

  store->put(StoredGoal{"r1", Goal{5, GoalMode::Direct, {1, 2}, 0.0, SquareAnchor::Corner}, 1000, false});
  store->put_home("r1", {3, 4});
  store->put_home("r1", {9, 9});  // the first home stays
  EXPECT_TRUE(store->dirty());
  ASSERT_TRUE(store->flush());
  EXPECT_FALSE(store->dirty());
  EXPECT_FALSE(fs::exists(path + ".tmp"));

  auto again = GoalStore::open(path);
  ASSERT_TRUE(again) << again.message();
  ASSERT_EQ(again->record().goals.count("r1"), 1u);
  EXPECT_EQ(again->record().goals.at("r1").goal.target, (Vec2{1, 2}));
  EXPECT_EQ(again->record().homes.at("r1"), (Vec2{3, 4}));
}

TEST(GoalStore, ReplaysAreStaleAndOnlyTheCurrentGoalFinishes) {
  auto store = GoalStore::open("");
  ASSERT_TRUE(store);
  store->put(StoredGoal{"r1", Goal{5, GoalMode::Planned, {1, 2}, 0.0, SquareAnchor::Corner}, 1000, false});
  EXPECT_TRUE(store->is_stale("r1", 1000));   // the same sample again
  EXPECT_TRUE(store->is_stale("r1", 999));    // an older goal from another writer's cache
  EXPECT_FALSE(store->is_stale("r1", 1001));  // a new goal
  EXPECT_FALSE(store->is_stale("r2", 0));     // nothing kept for r2

  store->finish("r1", 4);  // not the current goal
  EXPECT_FALSE(store->record().goals.at("r1").finished);
  store->finish("r1", 5);
  EXPECT_TRUE(store->record().goals.at("r1").finished);
  EXPECT_TRUE(goals_to_resume(store->record()).empty());
  EXPECT_TRUE(store->flush());  // memory only: nothing to write, no error
}

TEST(GoalStore, AFleetGoalFinishesWhenEveryRobotThatTookItHas) {
  auto store = GoalStore::open("");
  ASSERT_TRUE(store);
  const Goal explore{21, GoalMode::Explore, {}, 0.0, SquareAnchor::Corner};
  store->put(StoredGoal{"*", explore, 500, false});
  store->put(StoredGoal{"r1", explore, 500, false});
  store->put(StoredGoal{"r2", explore, 500, false});
  store->put(StoredGoal{"r3", Goal{22, GoalMode::Planned, {1, 1}, 0.0, SquareAnchor::Corner}, 600, false});
  store->finish("r1", 21);
  EXPECT_FALSE(store->record().goals.at("*").finished) << "r2 is still exploring";
  store->finish("r2", 21);
  EXPECT_TRUE(store->record().goals.at("*").finished);  // r3 has its own goal, not the fleet's
  ASSERT_EQ(goals_to_resume(store->record()).size(), 1u);
  EXPECT_EQ(goals_to_resume(store->record())[0].robot_id, "r3");
}

TEST(GoalStore, ABrokenFileIsRefusedWithItsPath) {
  testkit::TempDir dir("goal-store");
  const std::string path = (dir.path() / "goals.json").string();
  std::ofstream(path) << "{\"format\": \"slam-planner-goals\", \"version\": 1, \"goals\": [3]}";
  auto store = GoalStore::open(path);
  ASSERT_FALSE(store);
  EXPECT_NE(store.message().find(path), std::string::npos);
  EXPECT_NE(store.message().find("goals[0] must be an object"), std::string::npos);
  EXPECT_NE(store.message().find("delete it"), std::string::npos);
}

TEST(GoalStore, AnUnwritableFileIsAnErrorAndTheChangeIsKeptForLater) {
  testkit::TempDir dir("goal-store");
  const fs::path blocker = dir.path() / "not_a_dir";
  std::ofstream(blocker) << "x";
  auto store = GoalStore::open((blocker / "goals.json").string());
  ASSERT_TRUE(store) << store.message();
  store->put(StoredGoal{"r1", Goal{1, GoalMode::Stop, {}, 0.0, SquareAnchor::Corner}, 1, false});
  EXPECT_FALSE(store->flush());
  EXPECT_TRUE(store->dirty());
}

TEST(GoalStore, ResumedGoalsAndHomesDriveTheFleetAsBefore) {
  GoalRecord r;
  r.goals["r1"] = StoredGoal{"r1", Goal{21, GoalMode::Home, {}, 0.0, SquareAnchor::Corner}, 50, false};
  r.goals["*"] = StoredGoal{"*", Goal{20, GoalMode::Stop, {}, 0.0, SquareAnchor::Corner}, 40, false};
  r.homes["r1"] = Vec2{-3, 4};
  Fleet fleet({});
  for (const auto& [id, home] : r.homes) fleet.restore_home(id, home);
  for (const StoredGoal& g : goals_to_resume(r)) ASSERT_TRUE(fleet.set_goal(g.robot_id, g.goal));
  fleet.observe("r1", {10, 10});
  fleet.observe("r2", {1, 1});
  EXPECT_EQ(fleet.home("r1"), (Vec2{-3, 4}));  // where it was first seen before the restart
  EXPECT_EQ(fleet.home("r2"), (Vec2{1, 1}));
  EXPECT_EQ(fleet.tracker("r1")->mode(), GoalMode::Home);  // its own goal came after the fleet's
  EXPECT_EQ(fleet.tracker("r2")->mode(), GoalMode::Stop);  // the standing fleet goal
}

}  // namespace
}  // namespace slam::planner

namespace slam::planner {
namespace {

TEST(GoalRecord, MissionsRoundTripWithTheirProgress) {
  GoalRecord original;
  original.missions["r1"] =
      StoredMission{"r1", Mission{21, {{1, 2}, {3.5, -4}}, true},
                    MissionProgress{1, 7, MissionStatus::Active, "waypoint 0 skipped: x"}, 500};
  original.missions["r2"] =
      StoredMission{"r2", Mission{22, {{0, 0}}, false}, MissionProgress{0, 1, MissionStatus::Done, ""}, 400};
  auto parsed = parse_goal_record(format_goal_record(original));
  ASSERT_TRUE(parsed) << parsed.message();
  ASSERT_EQ(parsed->missions.size(), 2u);
  const StoredMission& m = parsed->missions.at("r1");
  EXPECT_EQ(m.mission.mission_id, 21u);
  EXPECT_EQ(m.mission.waypoints, (std::vector<Vec2>{{1, 2}, {3.5, -4}}));
  EXPECT_TRUE(m.mission.loop);
  EXPECT_EQ(m.progress, original.missions.at("r1").progress);
  EXPECT_EQ(m.sent_ns, 500);
  EXPECT_EQ(parsed->missions.at("r2").progress.status, MissionStatus::Done);
  const auto resume = missions_to_resume(*parsed);
  ASSERT_EQ(resume.size(), 1u);
  EXPECT_EQ(resume[0].robot_id, "r1");
}

TEST(GoalRecord, BadMissionsNameWhatIsWrong) {
  const std::string head = R"({"format": "slam-planner-goals", "version": 1, "missions": [)";
  const auto error_of = [&](const std::string& mission) {
    auto r = parse_goal_record(head + mission + "]}");
    return r ? std::string("accepted") : r.message();
  };
  const std::string good =
      R"({"robot_id": "a", "mission_id": 1, "waypoints": [[0, 0], [1, 1]], "loop": true, "current": 1, )"
      R"("laps": 0, "status": "active", "sent_ns": 5})";
  EXPECT_EQ(error_of(good), "accepted");
  EXPECT_NE(error_of(R"({"robot_id": "a"})").find("missions[0] has no \"mission_id\""), std::string::npos);
  std::string past_end = good;
  past_end.replace(past_end.find("\"current\": 1"), 12, "\"current\": 2");
  EXPECT_NE(error_of(past_end).find("missions[0]: mission current waypoint 2"), std::string::npos);
  std::string bad_status = good;
  bad_status.replace(bad_status.find("\"active\""), 8, "\"lost\"");
  EXPECT_NE(error_of(bad_status).find("missions[0].status must be one of active, done"), std::string::npos);
  EXPECT_NE(error_of(good + ", " + good).find("a second mission for robot 'a'"), std::string::npos);
}

TEST(GoalStore, AMissionAndAGoalReplaceEachOther) {
  auto store = GoalStore::open("");
  ASSERT_TRUE(store);
  store->put(StoredGoal{"r1", Goal{5, GoalMode::Planned, {1, 2}, 0.0, SquareAnchor::Corner}, 1000, false});
  const StoredMission mission{"r1", Mission{6, {{1, 1}, {2, 2}}, true}, {}, 2000};
  store->put_mission(mission);
  EXPECT_TRUE(store->record().goals.at("r1").finished);
  EXPECT_TRUE(store->is_stale("r1", 2000));
  EXPECT_TRUE(store->is_stale("r1", 1500));
  EXPECT_FALSE(store->is_stale("r1", 2001));
  EXPECT_EQ(missions_to_resume(store->record()).size(), 1u);

  store->put(StoredGoal{"r2", Goal{7, GoalMode::Stop, {}, 0.0, SquareAnchor::Corner}, 3000, false});
  EXPECT_EQ(store->record().missions.at("r1").progress.status, MissionStatus::Active)
      << "another robot's goal";
  store->put(StoredGoal{"r1", Goal{8, GoalMode::Home, {}, 0.0, SquareAnchor::Corner}, 3000, false});
  EXPECT_EQ(store->record().missions.at("r1").progress.status, MissionStatus::Cancelled);
  EXPECT_TRUE(missions_to_resume(store->record()).empty());
}

}  // namespace
}  // namespace slam::planner

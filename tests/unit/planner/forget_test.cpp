// Forgetting a robot in the planner's core: the fleet drops its tracker, home and kept goal, the
// goal store its goal, home and mission, the mission runner its mission (unreported); a robot that
// reports again starts afresh.
#include <gtest/gtest.h>

#include "planner/core/fleet.hpp"
#include "planner/core/goal_store.hpp"

namespace slam::planner {
namespace {

TEST(FleetForget, DropsTrackerHomeAndKeptGoal) {
  Fleet fleet({});
  fleet.observe("a", {1, 1});
  ASSERT_TRUE(fleet.set_goal("a", Goal{7, GoalMode::Direct, {5, 5}, 0, {}}));
  ASSERT_TRUE(fleet.set_goal("later", Goal{8, GoalMode::Stop, {}, 0, {}}));
  fleet.forget("a");
  fleet.forget("later");
  EXPECT_EQ(fleet.tracker("a"), nullptr);
  EXPECT_FALSE(fleet.home("a"));
  EXPECT_EQ(fleet.pending_goal("later"), nullptr);
  EXPECT_EQ(fleet.size(), 0u);

  fleet.observe("a", {3, 4});
  ASSERT_NE(fleet.tracker("a"), nullptr);
  EXPECT_NE(fleet.tracker("a")->status(), GoalStatus::Active) << "the old goal is gone";
  EXPECT_EQ(*fleet.home("a"), (Vec2{3, 4})) << "home is the new first position";
}

TEST(FleetForget, RestoredHomeIsForgottenToo) {
  Fleet fleet({});
  fleet.restore_home("a", {9, 9});
  fleet.forget("a");
  fleet.observe("a", {1, 2});
  EXPECT_EQ(*fleet.home("a"), (Vec2{1, 2}));
}

TEST(GoalStoreForget, DropsGoalHomeAndMission) {
  auto store = GoalStore::open("");
  ASSERT_TRUE(store);
  store->put(StoredGoal{"a", Goal{7, GoalMode::Direct, {5, 5}, 0, {}}, 100, false});
  store->put_home("a", {1, 1});
  StoredMission mission;
  mission.robot_id = "a";
  mission.mission.waypoints = {{1, 1}, {2, 2}};
  store->put_mission(mission);
  ASSERT_TRUE(store->flush());
  store->forget("a");
  EXPECT_TRUE(store->dirty());
  EXPECT_EQ(store->record().goals.count("a"), 0u);
  EXPECT_EQ(store->record().homes.count("a"), 0u);
  EXPECT_EQ(store->record().missions.count("a"), 0u);
  EXPECT_FALSE(store->is_stale("a", 50)) << "no goal kept: an older one is new again";
  ASSERT_TRUE(store->flush());
  store->forget("a");
  EXPECT_FALSE(store->dirty()) << "forgetting an unknown robot changes nothing";
}

}  // namespace
}  // namespace slam::planner

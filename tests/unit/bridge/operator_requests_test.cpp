#include "bridge/core/operator_requests.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace slam::bridge {
namespace {

TEST(OperatorRequests, ParsesAPlannedGoalByDefault) {
  auto goal = parse_goal(R"({"robot_id": "sim-1", "x": 2.5, "y": -1})");
  ASSERT_TRUE(goal) << goal.message();
  EXPECT_EQ(goal->robot_id, "sim-1");
  EXPECT_EQ(goal->mode, msg::GoalMode::Planned);
  EXPECT_EQ(goal->target, (Vec2{2.5, -1.0}));
}

TEST(OperatorRequests, ExploreNeedsNoTarget) {
  auto goal = parse_goal(R"({"robot_id": "*", "mode": "explore"})");
  ASSERT_TRUE(goal) << goal.message();
  EXPECT_EQ(goal->mode, msg::GoalMode::Explore);
}

TEST(OperatorRequests, RefusesBadGoals) {
  for (const char* text : {"not json", "[]", R"({"x": 1, "y": 2})", R"({"robot_id": "", "x": 1, "y": 2})",
                           R"({"robot_id": "a", "x": 1})", R"({"robot_id": "a", "x": "1", "y": 2})",
                           R"({"robot_id": "a", "mode": "fly"})", R"({"robot_id": "a", "mode": "square"})"})
    EXPECT_FALSE(parse_goal(text)) << text;
}

TEST(OperatorRequests, ParsesAPathQueryWithDefaults) {
  auto q = parse_path_query(R"({"start": {"x": 0, "y": 1}, "goal": {"x": 3, "y": 4}})");
  ASSERT_TRUE(q) << q.message();
  EXPECT_EQ(q->start, (Vec2{0, 1}));
  EXPECT_EQ(q->goal, (Vec2{3, 4}));
  EXPECT_EQ(q->algorithm, "astar");
  EXPECT_GT(q->time_budget_s, 0.0);
  EXPECT_FALSE(parse_path_query(R"({"start": {"x": 0}, "goal": {"x": 3, "y": 4}})"));
  EXPECT_FALSE(
      parse_path_query(R"({"start": {"x": 0, "y": 0}, "goal": {"x": 3, "y": 4}, "time_budget_s": 0})"));
}

TEST(OperatorRequests, AnswersInTheResponseSchemasFields) {
  const auto j =
      nlohmann::json::parse(path_answer_json({3, msg::PlanStatus::Ok, "", {{0, 0}, {1, 2}}, 2.2, 0.01}));
  EXPECT_EQ(j["status"], "ok");
  ASSERT_EQ(j["path"].size(), 2u);
  EXPECT_EQ(j["path"][1]["y"], 2.0);
  EXPECT_EQ(j["length_m"], 2.2);
}

}  // namespace
}  // namespace slam::bridge

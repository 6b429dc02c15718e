// Click actions: which command a click sends, and their names.
#include "viewer/core/click_actions.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

TEST(ClickActions, TargetSendsGoalForTheSelectedRobot) {
  const auto out = click_outcome(ClickAction::SetTarget, {1.0, 2.0}, "r1", GoalMode::Planned, 2.0, true);
  ASSERT_TRUE(out.goal);
  EXPECT_FALSE(out.edit);
  EXPECT_EQ(out.goal->robot_id, "r1");
  EXPECT_EQ(out.goal->mode, GoalMode::Planned);
  EXPECT_DOUBLE_EQ(out.goal->target.y, 2.0);
  EXPECT_TRUE(out.goal->square_centred);
}

TEST(ClickActions, ModesWithoutTargetBecomeDirect) {
  const auto out = click_outcome(ClickAction::SetTarget, {}, "*", GoalMode::Explore, 1.0, false);
  ASSERT_TRUE(out.goal);
  EXPECT_EQ(out.goal->mode, GoalMode::Direct);
}

TEST(ClickActions, ObstructAndUnobstructSendMapEdits) {
  auto o = click_outcome(ClickAction::Obstruct, {3.0, 4.0}, "r1", GoalMode::Direct, 1.0, false);
  ASSERT_TRUE(o.edit);
  EXPECT_EQ(o.edit->kind, MapEditKind::Obstruct);
  EXPECT_DOUBLE_EQ(o.edit->point.x, 3.0);
  auto u = click_outcome(ClickAction::Unobstruct, {}, "r1", GoalMode::Direct, 1.0, false);
  ASSERT_TRUE(u.edit);
  EXPECT_EQ(u.edit->kind, MapEditKind::Unobstruct);
  auto n = click_outcome(ClickAction::Nothing, {}, "r1", GoalMode::Direct, 1.0, false);
  EXPECT_FALSE(n.goal);
  EXPECT_FALSE(n.edit);
}

TEST(ClickActions, NamesRoundTrip) {
  for (auto a :
       {ClickAction::Nothing, ClickAction::SetTarget, ClickAction::Obstruct, ClickAction::Unobstruct}) {
    auto parsed = parse_click_action(click_action_name(a));
    ASSERT_TRUE(parsed);
    EXPECT_EQ(*parsed, a);
  }
  EXPECT_FALSE(parse_click_action("explode"));
}

}  // namespace
}  // namespace slam::viewer

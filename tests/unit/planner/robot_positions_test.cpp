// RobotPositions: the newest position per robot wins, whichever source offered it, and a take
// hands over each robot once.
#include "planner/core/robot_positions.hpp"

#include <gtest/gtest.h>

namespace slam::planner {
namespace {

TEST(RobotPositions, EachRobotIsTakenOnceWithItsNewestPosition) {
  RobotPositions positions;
  EXPECT_TRUE(positions.offer("a", {1.0, 1.0}, 100));
  EXPECT_TRUE(positions.offer("b", {5.0, 5.0}, 100));
  EXPECT_TRUE(positions.offer("a", {2.0, 1.0}, 200));
  std::vector<RobotPosition> out;
  positions.take(out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].robot_id, "a");
  EXPECT_EQ(out[0].position, (Vec2{2.0, 1.0}));
  EXPECT_EQ(out[0].last_seen_ns, 200);
  EXPECT_EQ(out[1].robot_id, "b");
  positions.take(out);
  EXPECT_TRUE(out.empty());
}

// A slow state record arriving after the digest that already placed a later message.
TEST(RobotPositions, AnOlderPositionIsDroppedEvenInALaterRound) {
  RobotPositions positions;
  EXPECT_TRUE(positions.offer("a", {2.0, 0.0}, 200));
  std::vector<RobotPosition> out;
  positions.take(out);
  EXPECT_FALSE(positions.offer("a", {1.0, 0.0}, 150));
  positions.take(out);
  EXPECT_TRUE(out.empty());
}

// The same message placed again through a newer correction moves the robot.
TEST(RobotPositions, AnEqualStampIsTaken) {
  RobotPositions positions;
  EXPECT_TRUE(positions.offer("a", {2.0, 0.0}, 200));
  EXPECT_TRUE(positions.offer("a", {2.1, 0.0}, 200));
  std::vector<RobotPosition> out;
  positions.take(out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].position, (Vec2{2.1, 0.0}));
}

// A position offered before the forget but not yet taken goes with it; a digest still listing
// the robot with its last stamp does not bring it back, a newer message does.
TEST(RobotPositions, AForgottenRobotIsDroppedUntilItSpeaksAgain) {
  RobotPositions positions;
  EXPECT_TRUE(positions.offer("a", {2.0, 0.0}, 200));
  EXPECT_TRUE(positions.offer("b", {3.0, 0.0}, 200));
  EXPECT_TRUE(positions.offer("c", {4.0, 0.0}, 200));
  positions.forget("a");
  EXPECT_FALSE(positions.offer("a", {2.0, 0.0}, 200));
  EXPECT_TRUE(positions.offer("c", {4.5, 0.0}, 210));
  std::vector<RobotPosition> out;
  positions.take(out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].robot_id, "b");
  EXPECT_EQ(out[1].robot_id, "c");
  EXPECT_EQ(out[1].position, (Vec2{4.5, 0.0}));
  EXPECT_TRUE(positions.offer("a", {0.5, 0.0}, 300));
  positions.take(out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].position, (Vec2{0.5, 0.0}));
}

}  // namespace
}  // namespace slam::planner

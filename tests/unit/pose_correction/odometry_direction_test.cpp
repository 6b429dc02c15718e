// OdometryDirection: odometry that counts backward driving as forward is turned round while the
// matches show the robot reversing, and turned back when they show it going ahead again; odometry
// whose sign is right, short motions and a match's noise never turn it.
#include "pose_correction/odometry_direction.hpp"

#include <gtest/gtest.h>

#include <random>

namespace slam::correction {
namespace {

TEST(OdometryDirection, ANewRobotsOdometryIsTakenAsItIs) {
  const OdometryDirection direction;
  const Pose motion{0.3, 0.02, 0.1};
  EXPECT_FALSE(direction.reversed());
  EXPECT_EQ(direction.applied(motion).x, motion.x);
  EXPECT_EQ(direction.applied(motion).y, motion.y);
}

TEST(OdometryDirection, OdometryWithItsSignRightIsNeverTurned) {
  OdometryDirection direction;
  std::mt19937 rng(3);
  std::normal_distribution<double> match_noise(0.0, 0.05);  // a poor match, a tenth of a metre off
  for (int i = 0; i < 1000; ++i) {
    const Pose odom{0.1 + 0.001 * (i % 200), 0.0, 0.0};
    direction.learn(odom, Pose{odom.x + match_noise(rng), match_noise(rng), 0.0});
    ASSERT_FALSE(direction.reversed()) << "keyframe " << i;
  }
}

TEST(OdometryDirection, AReversingRobotsOdometryIsTurnedRoundUntilItGoesAheadAgain) {
  OdometryDirection direction;
  const Pose counted{0.3, 0.04, 0.1};  // what the odometry counts, both ways
  const Pose backwards{-0.3, -0.04, 0.1};
  direction.learn(counted, backwards);
  ASSERT_TRUE(direction.reversed());
  const Pose applied = direction.applied(counted);
  EXPECT_DOUBLE_EQ(applied.x, backwards.x);
  EXPECT_DOUBLE_EQ(applied.y, backwards.y);
  EXPECT_DOUBLE_EQ(applied.theta, backwards.theta);
  direction.learn(counted, backwards);  // still reversing
  EXPECT_TRUE(direction.reversed());
  direction.learn(counted, counted);  // ahead again
  EXPECT_FALSE(direction.reversed());
}

TEST(OdometryDirection, ShortAndUnclearMotionsTeachNothing) {
  OdometryDirection direction;
  direction.learn(Pose{0.03, 0.0, 0.0}, Pose{-0.03, 0.0, 0.0});  // shorter than kMinTravel_m
  EXPECT_FALSE(direction.reversed());
  direction.learn(Pose{0.3, 0.0, 0.0}, Pose{-0.1, 0.25, 0.0});  // mostly sideways: no clear sign
  EXPECT_FALSE(direction.reversed());
}

}  // namespace
}  // namespace slam::correction

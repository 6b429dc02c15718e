// The laser's place on the robot from static transforms: chains composed, unlinked frames and loops
// refused, a laser mounted upside down reported as mirrored.
#include "simulator/robot_log/laser_mount.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace slam::robot_log {
namespace {

constexpr double kPi = std::numbers::pi;

Ros2Transform link(std::string parent, std::string child, Vec3d t, Quaternion q) {
  Ros2Transform out;
  out.header.frame_id = std::move(parent);
  out.child_frame_id = std::move(child);
  out.translation = t;
  out.rotation = q;
  return out;
}

Quaternion yaw(double a) {
  return {0, 0, std::sin(a / 2), std::cos(a / 2)};
}

TEST(LaserMount, ComposesAChainOfStaticTransforms) {
  StaticFrames frames;
  EXPECT_TRUE(frames.empty());
  frames.add(link("base_footprint", "base_link", {0.1, 0, 0.2}, yaw(kPi / 2)));
  frames.add(link("/base_link", "/laser", {0.2, 0.1, 0.1}, yaw(0.5)));
  const auto mount = frames.mount("base_footprint", "laser");
  ASSERT_TRUE(mount);
  // base_link is turned 90 degrees: its (0.2, 0.1) is (-0.1, 0.2) in base_footprint.
  EXPECT_NEAR(mount->in_robot.x, 0.0, 1e-12);
  EXPECT_NEAR(mount->in_robot.y, 0.2, 1e-12);
  EXPECT_NEAR(mount->in_robot.theta, kPi / 2 + 0.5, 1e-12);
  EXPECT_FALSE(mount->mirrored);
  EXPECT_EQ(frames.mount("base_link", "base_link")->in_robot, Pose{});
}

TEST(LaserMount, UnlinkedFramesAndLoopsGiveNothing) {
  StaticFrames frames;
  frames.add(link("base_link", "laser", {0.2, 0, 0}, yaw(0)));
  EXPECT_FALSE(frames.mount("base_footprint", "laser"));
  EXPECT_FALSE(frames.mount("base_link", "camera"));
  frames.add(link("a", "b", {}, yaw(0)));
  frames.add(link("b", "a", {}, yaw(0)));
  EXPECT_FALSE(frames.mount("base_link", "a"));
}

TEST(LaserMount, UpsideDownLaserIsMirrored) {
  StaticFrames frames;
  // Rolled by pi about its x axis, then turned 0.3 rad; quaternions need not be normalised.
  const Quaternion roll{2, 0, 0, 0};
  const Quaternion q = yaw(0.3);
  frames.add(link("base_link", "laser_mount", {0.1, 0, 0}, q));
  frames.add(link("laser_mount", "laser", {}, roll));
  const auto mount = frames.mount("base_link", "laser");
  ASSERT_TRUE(mount);
  EXPECT_TRUE(mount->mirrored);
  EXPECT_NEAR(mount->in_robot.theta, 0.3, 1e-12);
  EXPECT_NEAR(mount->in_robot.x, 0.1, 1e-12);
}

}  // namespace
}  // namespace slam::robot_log

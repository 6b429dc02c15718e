// A robot's trajectory from the store: each observation placed by its keyframe's stored correction
// (or the robot's nearest earlier one), stamped by the robot's clock when it sent one, other robots
// left out; the TUM and CARMEN lines; and the failures a trajectory request is answered with.
#include "mapper/core/trajectory_export.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace slam::mapper {
namespace {

constexpr double kQuarter = std::numbers::pi / 2;

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class TrajectoryExport : public ::testing::Test {
 protected:
  TrajectoryExport() {
    auto opened = ObservationStore::open(dir_.path() / "m.db");
    EXPECT_TRUE(opened.is_ok()) << opened.message();
    store_.emplace(std::move(*opened));
  }

  void append(const std::string& robot, int64_t stamp_ns, KeyframeId keyframe, Pose odom, bool heading,
              int64_t robot_stamp_ns) {
    const ObservationView v{odom.x, odom.y, heading ? odom.theta : 0.0, heading, {}, {}};
    ASSERT_TRUE(store_->append(robot, ++seq_, stamp_ns, keyframe, v, robot_stamp_ns));
  }

  // r1: keyframes 1 (a quarter turn) and 3 (shifted by (10, 0)); r2: keyframe 2, never r1's.
  void two_robots() {
    const std::vector<Keyframe> keyframes{{1, "r1", 0, Pose{}, Pose{0.0, 0.0, kQuarter}},
                                          {2, "r2", 0, Pose{}, Pose{-5.0, -5.0, 0.0}},
                                          {3, "r1", 0, Pose{}, Pose{10.0, 0.0, 0.0}}};
    ASSERT_TRUE(store_->save_keyframes(keyframes));
    append("r1", 1'000, 0, {1.0, 0.0, 0.0}, true, 0);       // before any keyframe: identity
    append("r1", 2'000, 1, {1.0, 0.0, 0.0}, true, 5'000);   // keyframe 1
    append("r2", 2'500, 2, {0.0, 0.0, 0.0}, true, 0);       // another robot
    append("r1", 3'000, 0, {2.0, 0.0, 0.0}, false, 0);      // none: keyframe 1 before it
    append("r1", 4'000, 3, {0.0, 1.0, 0.5}, true, 7'000);   // keyframe 3
    append("r1", 5'000, 99, {0.0, 2.0, 0.0}, true, 8'000);  // a keyframe never stored: keyframe 3 before it
  }

  testkit::TempDir dir_{"trajectory"};
  std::optional<ObservationStore> store_;
  uint64_t seq_ = 0;
};

TEST_F(TrajectoryExport, PlacesEachObservationByItsKeyframesCorrection) {
  two_robots();
  auto poses = robot_trajectory(*store_, "r1");
  ASSERT_TRUE(poses.is_ok()) << poses.message();
  ASSERT_EQ(poses->size(), 5u);
  const auto expect_pose = [&](size_t i, double x, double y, double theta) {
    const Pose& p = (*poses)[i].pose;
    EXPECT_NEAR(p.x, x, 1e-12) << "pose " << i;
    EXPECT_NEAR(p.y, y, 1e-12) << "pose " << i;
    EXPECT_NEAR(p.theta, theta, 1e-12) << "pose " << i;
  };
  expect_pose(0, 1.0, 0.0, 0.0);
  expect_pose(1, 0.0, 1.0, kQuarter);
  expect_pose(2, 0.0, 2.0, 0.0);  // no heading: theta stays 0
  expect_pose(3, 10.0, 1.0, 0.5);
  expect_pose(4, 10.0, 2.0, 0.0);
  EXPECT_FALSE((*poses)[2].has_heading);
  EXPECT_TRUE((*poses)[3].has_heading);

  auto r2 = robot_trajectory(*store_, "r2");
  ASSERT_TRUE(r2.is_ok());
  ASSERT_EQ(r2->size(), 1u);
  EXPECT_EQ(r2->front().pose, (Pose{-5.0, -5.0, 0.0}));
  auto nobody = robot_trajectory(*store_, "r");
  ASSERT_TRUE(nobody.is_ok());
  EXPECT_TRUE(nobody->empty());
}

TEST_F(TrajectoryExport, StampsAreTheRobotsClockWhenItSentOneElseArrival) {
  two_robots();
  auto poses = robot_trajectory(*store_, "r1");
  ASSERT_TRUE(poses.is_ok()) << poses.message();
  std::vector<int64_t> stamps;
  for (const TrajectoryPose& p : *poses) stamps.push_back(p.stamp_ns);
  EXPECT_EQ(stamps, (std::vector<int64_t>{1'000, 5'000, 3'000, 7'000, 8'000}));
}

TEST_F(TrajectoryExport, WritesTumLines) {
  const std::vector<TrajectoryPose> poses{{1'763'800'000'123'456'789, {1.5, -2.25, kQuarter}, true},
                                          {12'500'000'000, {0.0, 0.125, 0.0}, false}};
  const auto path = dir_.path() / "out.tum";
  ASSERT_TRUE(write_trajectory(poses, path, TrajectoryFormat::Tum));
  EXPECT_EQ(read(path),
            "1763800000.123456789 1.500000 -2.250000 0 0 0 0.707106781 0.707106781\n"
            "12.500000000 0.000000 0.125000 0 0 0 0.000000000 1.000000000\n");
}

TEST_F(TrajectoryExport, WritesCarmenLines) {
  const std::vector<TrajectoryPose> poses{{12'500'000'000, {1.5, -2.25, -0.5}, true}};
  const auto path = dir_.path() / "out.log";
  ASSERT_TRUE(write_trajectory(poses, path, TrajectoryFormat::Carmen));
  EXPECT_EQ(read(path), "ODOM 1.500000 -2.250000 -0.500000 0 0 0 12.500000000 slamfleet 12.500000000\n");
  EXPECT_FALSE(write_trajectory(poses, dir_.path() / "missing" / "out.log", TrajectoryFormat::Carmen));
}

TEST_F(TrajectoryExport, FormatsByName) {
  EXPECT_EQ(trajectory_format_named("tum"), TrajectoryFormat::Tum);
  EXPECT_EQ(trajectory_format_named("carmen"), TrajectoryFormat::Carmen);
  EXPECT_FALSE(trajectory_format_named("TUM"));
  EXPECT_FALSE(trajectory_format_named(""));
}

TEST_F(TrajectoryExport, AFileRequestSaysWhatItWroteOrWhyNot) {
  two_robots();
  const std::string path = (dir_.path() / "r1.tum").string();
  const FileOutcome done = export_trajectory_file(*store_, "r1", path, TrajectoryFormat::Tum);
  ASSERT_TRUE(done.ok()) << done.message;
  EXPECT_EQ(done.message, "wrote 5 poses of robot 'r1' (0.000001000 to 0.000008000 s) to " + path);
  const std::string text = read(path);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 5);
  EXPECT_EQ(text.substr(0, text.find(' ')), "0.000001000");

  const auto failure = [&](std::string_view robot, const std::string& file) {
    return export_trajectory_file(*store_, robot, file, TrajectoryFormat::Tum);
  };
  EXPECT_EQ(failure("ghost", path).failure, MapError::UnknownRobot);
  EXPECT_NE(failure("ghost", path).message.find("ghost"), std::string::npos);
  EXPECT_EQ(failure("", path).failure, MapError::InvalidRequest);
  EXPECT_EQ(failure("r1", "").failure, MapError::InvalidRequest);
  EXPECT_EQ(failure("r1", std::string("a\0b", 3)).failure, MapError::InvalidRequest);
  const FileOutcome no_dir = failure("r1", "/nonexistent-dir/r1.tum");
  EXPECT_EQ(no_dir.failure, MapError::Io);
  EXPECT_NE(no_dir.message.find("/nonexistent-dir"), std::string::npos) << no_dir.message;
  EXPECT_EQ(failure("r1", dir_.path().string()).failure, MapError::Io);  // a directory, not a file
}

}  // namespace
}  // namespace slam::mapper

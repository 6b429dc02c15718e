// A laser robot whose odometry counts backing up as driving forward (as Freiburg 079's does) is
// followed: by the wider search of a match on its window's edge, and along a corridor, where no match
// can tell, by its odometry turned round (OdometryDirection).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "pose_correction/pose_corrector.hpp"
#include "room_scene.hpp"

namespace slam::correction {
namespace {

using testing_scene::laser_hits;
using testing_scene::room;
using testing_scene::Wall;
using TrueMap = testing_scene::WallMap;

// A laser robot (180 beams, 8 m) that drives 2 m forward, then backs up 1.5 m while its odometry
// goes on integrating forward (as Freiburg 079's robot does): 0.24 m of error per scan keyframe,
// beyond the tracking window. The wider search of a match on its window's edge follows the truth;
// without it the robot is placed metres off.
double backing_up_error(const CorrectorOptions& options) {
  const TrueMap map(room());
  PoseCorrector corrector(options);
  std::vector<KeyframeCorrection> finalised;
  const auto walls = room();
  Pose truth{1.0, 1.0, 0.0}, belief = truth;
  int64_t stamp = 0;
  std::vector<std::pair<Pose, Pose>> belief_and_truth;
  const auto step = [&](double truth_dx) {
    truth = truth.compose({truth_dx, 0.0, 0.0});
    belief = belief.compose({0.03, 0.0, 0.0});
    belief_and_truth.emplace_back(belief, truth);
    stamp += 100'000'000;
    EXPECT_TRUE(corrector.add("r1", stamp, belief, true, laser_hits(walls, truth, belief)));
    corrector.process(map.view(), stamp, finalised);
  };
  for (int i = 0; i < 66; ++i) step(0.03);
  for (int i = 0; i < 50; ++i) step(-0.03);
  EXPECT_GT(distance(belief.position(), truth.position()), 2.5);
  EXPECT_GT(corrector.stats().matched, 20);
  corrector.finish();
  corrector.process(map.view(), stamp, finalised);
  // Scored where the last keyframe starts. Within a keyframe odometry carries the scans: backing up,
  // its four scans lie up to 0.18 m apart from where they were taken, and the match places the blend.
  if (finalised.empty()) return 1e9;
  const KeyframeCorrection& last = finalised.back();
  const auto at = std::find_if(belief_and_truth.begin(), belief_and_truth.end(), [&](const auto& pair) {
    return distance(pair.first.position(), last.odom.position()) < 1e-9;
  });
  if (at == belief_and_truth.end()) return 1e9;
  return distance(last.correction.compose(last.odom).position(), at->second.position());
}

TEST(PoseCorrector, ALaserRobotBackingUpWhileItsOdometrySaysForwardIsFollowed) {
  EXPECT_LT(backing_up_error(CorrectorOptions{}), 0.1);
  CorrectorOptions without;
  without.scan_recovery_window = without.scan_track_window;
  EXPECT_GT(backing_up_error(without), 0.5);
}

// The same robot backs out of a room into a corridor longer than its laser's reach, its odometry
// still counting forward. Along the corridor no match can tell where it is: the prediction decides,
// and only odometry turned round (OdometryDirection, learned where the room's walls pinned the
// reversal) keeps it with the truth.
double backing_into_corridor_error(const CorrectorOptions& options) {
  // A 4 x 4 m room with a pillar, its east wall open at y 1.5..2.5 into a corridor 1 m wide.
  const std::vector<Wall> walls{{{0, 0}, {4, 0}},       {{0, 4}, {4, 4}},      {{0, 0}, {0, 4}},
                                {{4, 0}, {4, 1.5}},     {{4, 2.5}, {4, 4}},    {{1, 1}, {1.5, 1}},
                                {{1.5, 1}, {1.5, 1.4}}, {{4, 1.5}, {30, 1.5}}, {{4, 2.5}, {30, 2.5}}};
  const TrueMap map(walls, GridGeometry{{-0.525, -0.525}, 0.05, 640, 100});
  PoseCorrector corrector(options);
  std::vector<KeyframeCorrection> finalised;
  Pose truth{3.5, 2.0, std::numbers::pi}, belief = truth;  // facing the room, the corridor behind
  int64_t stamp = 0;
  const auto step = [&](double truth_dx) {
    truth = truth.compose({truth_dx, 0.0, 0.0});
    belief = belief.compose({std::abs(truth_dx), 0.0, 0.0});
    stamp += 100'000'000;
    EXPECT_TRUE(corrector.add("r1", stamp, belief, true, laser_hits(walls, truth, belief)));
    corrector.process(map.view(), stamp, finalised);
  };
  for (int i = 0; i < 40; ++i) step(0.03);    // 1.2 m into the room
  for (int i = 0; i < 300; ++i) step(-0.03);  // backs out, 7.8 m along the corridor
  corrector.finish();
  corrector.process(map.view(), stamp, finalised);
  return distance(corrector.correction("r1").compose(belief).position(), truth.position());
}

TEST(PoseCorrector, OdometryTurnedRoundCarriesABackingRobotAlongACorridor) {
  const double with = backing_into_corridor_error(CorrectorOptions{});
  CorrectorOptions without;
  without.odometry_direction = false;
  const double error_without = backing_into_corridor_error(without);
  RecordProperty("error_mm", static_cast<int>(with * 1000));
  RecordProperty("error_without_mm", static_cast<int>(error_without * 1000));
  EXPECT_LT(with, 0.3);
  EXPECT_GT(error_without, 2.0);
}

}  // namespace
}  // namespace slam::correction

// A sparse robot that comes back from a long loop metres off, beyond the loop-closure window, is
// found again by its recent trail (CorrectorOptions::relocalise_sigma_m).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "pose_correction/pose_corrector.hpp"
#include "room_scene.hpp"

namespace slam::correction {
namespace {

using testing_scene::cast;
using testing_scene::Wall;

// A ring corridor 2 m wide around an 8 x 4 m block. A short stub at the start's corner makes the
// corner where the loop closes unlike the other three.
std::vector<Wall> ring() {
  return {{{0, 0}, {12, 0}}, {{12, 0}, {12, 8}}, {{12, 8}, {0, 8}},
          {{0, 8}, {0, 0}},  {{2, 2}, {10, 2}},  {{10, 2}, {10, 6}},
          {{10, 6}, {2, 6}}, {{2, 6}, {2, 2}},   {{0.6, 1.2}, {1.0, 1.2}}};
}

// 12 beams over 360 degrees, 4 m range: a sparse robot. Hits in the robot's odometry frame.
std::vector<Vec2> sense(const std::vector<Wall>& walls, const Pose& truth, const Pose& odometry, int step) {
  std::vector<Vec2> hits;
  for (int i = 0; i < 12; ++i) {
    const double a = truth.theta + 2.0 * std::numbers::pi * (i + 0.37 * step) / 12.0;
    const Vec2 dir{std::cos(a), std::sin(a)};
    if (auto t = cast(walls, truth.position(), dir, 4.0))
      hits.push_back(odometry.compose(truth.inverse()).transform(truth.position() + dir * *t));
  }
  return hits;
}

// Drives `robot` from corners[0] through the others, 3 cm a message, its odometry starting at the
// truth and its heading drifting `drift` rad a message. The corrector sees no grid (nothing to track
// against): only old keyframes can bring the robot back. Returns the odometry at the end.
struct Drive {
  Pose truth;
  Pose odometry;
};
Drive drive(PoseCorrector& corrector, const std::string& robot, const std::vector<Vec2>& corners,
            double drift, int64_t& stamp) {
  const auto walls = ring();
  const GridView no_grid{};
  std::vector<KeyframeCorrection> finalised;
  const Vec2 first = corners[1] - corners[0];
  Pose truth{corners[0].x, corners[0].y, std::atan2(first.y, first.x)};
  Pose odometry = truth;
  int step = 0;
  for (size_t c = 1; c < corners.size(); ++c) {
    while (distance(truth.position(), corners[c]) > 0.02) {
      const Vec2 to = corners[c] - truth.position();
      const double heading = std::atan2(to.y, to.x);
      const double d = std::min(0.03, norm(to));
      const Pose turn{0, 0, wrap_angle(heading - truth.theta)};
      truth = Pose{truth.x, truth.y, heading}.compose(Pose{d, 0, 0});
      odometry = odometry.compose(turn).compose(Pose{d, 0, drift});
      stamp += 100'000'000;
      ++step;
      EXPECT_TRUE(corrector.add(robot, stamp, odometry, true, sense(walls, truth, odometry, step)));
      corrector.process(no_grid, stamp, finalised);
    }
  }
  corrector.finish();
  stamp += 1'000'000'000;
  corrector.process(no_grid, stamp, finalised);
  return {truth, odometry};
}

struct LoopResult {
  double raw_error_m = 0.0;        // odometry against the truth at the end
  double corrected_error_m = 0.0;  // the corrected pose against the truth at the end
};

// Once around the ring's centre line and on past the start.
LoopResult drive_loop(PoseCorrector& corrector, double drift) {
  int64_t stamp = 0;
  const Drive d = drive(corrector, "r1", {{1, 1}, {11, 1}, {11, 7}, {1, 7}, {1, 1}, {5, 1}}, drift, stamp);
  return {distance(d.odometry.position(), d.truth.position()),
          distance(corrector.correction("r1").compose(d.odometry).position(), d.truth.position())};
}

CorrectorOptions loop_options() {
  CorrectorOptions o;
  o.old_age_s = 10.0;      // the start is old map when the robot comes back to it
  o.wall_heading = false;  // no walls' heading to lean on: the trail alone
  o.odometry_calibration = false;
  o.relocalise = true;
  // The robot's odometry is known to be poor (its heading drifts 1 degree a metre), and its model says
  // so: a pose's sigma is what the search trusts to tell a lost robot.
  o.odom_sigma_rad_per_m = 0.05;
  return o;
}

TEST(PoseCorrectorRelocalise, ALoopBeyondTheClosureWindowIsClosedByTheTrail) {
  PoseCorrector corrector(loop_options());
  const LoopResult r = drive_loop(corrector, 0.0005);
  RecordProperty("raw_error_mm", static_cast<int>(r.raw_error_m * 1000));
  RecordProperty("corrected_error_mm", static_cast<int>(r.corrected_error_m * 1000));
  EXPECT_GT(r.raw_error_m, 1.2);  // beyond the 1 m closure window
  EXPECT_LT(r.corrected_error_m, 0.3);
  EXPECT_GT(corrector.stats().trail_searches, 0);
  EXPECT_GT(corrector.stats().closures_accepted, 0);
}

TEST(PoseCorrectorRelocalise, WithoutTheTrailSearchTheLoopStaysOpen) {
  CorrectorOptions o = loop_options();
  o.relocalise = false;
  PoseCorrector corrector(o);
  const LoopResult r = drive_loop(corrector, 0.0005);
  EXPECT_GT(r.corrected_error_m, 1.0);
}

// A robot switched on at a trusted start beside another robot's keyframes has no tie yet, but its pose
// is known: it is not searched for (in a building of look-alike rooms the trail could fit a wrong one).
TEST(PoseCorrectorRelocalise, ARobotAtItsTrustedStartIsNotSearchedFor) {
  PoseCorrector corrector(loop_options());
  int64_t stamp = 0;
  (void)drive(corrector, "r1", {{1, 1}, {11, 1}, {11, 7}, {1, 7}, {1, 3}}, 0.0, stamp);
  const int64_t searched_before = corrector.stats().trail_searches;
  const Drive d = drive(corrector, "r2", {{1, 2}, {1, 1}, {8, 1}}, 0.0, stamp);
  EXPECT_EQ(corrector.stats().trail_searches, searched_before);
  EXPECT_LT(distance(corrector.correction("r2").compose(d.odometry).position(), d.truth.position()), 0.1);
}

}  // namespace
}  // namespace slam::correction

// OdometryCalibration: a robot's systematic heading error (drift per metre, turn scale) is learned
// from its matches and taken out of its odometry; exact odometry stays uncorrected, and matches that
// do not pin the heading teach nothing.
#include "pose_correction/odometry_calibration.hpp"

#include <gtest/gtest.h>

#include <random>

namespace slam::correction {
namespace {

constexpr double kMatchVariance = 0.01 * 0.01;  // a sparse keyframe's heading, well pinned
constexpr double kOdomVariance = 0.008 * 0.008;

// Keyframes 0.4 m apart turning at random, from odometry whose turns are off by `turn_scale` and
// which drifts `drift` rad per metre; each match reads the true heading with 0.01 rad of noise.
void drive(OdometryCalibration& calibration, double drift, double turn_scale, int keyframes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> turn(-0.4, 0.4);
  std::normal_distribution<double> match_noise(0.0, 0.01);
  for (int i = 0; i < keyframes; ++i) {
    const Pose odom_motion{0.4, 0.0, turn(rng)};
    const double true_turn = odom_motion.theta * (1.0 + turn_scale) + drift * 0.4;
    const double predicted_turn = calibration.corrected(odom_motion).theta;
    calibration.learn(odom_motion, true_turn + match_noise(rng) - predicted_turn, kMatchVariance,
                      kOdomVariance);
  }
}

TEST(OdometryCalibration, ANewRobotsOdometryIsTakenAsItIs) {
  const OdometryCalibration calibration;
  const Pose motion{0.5, 0.1, 0.3};
  const Pose corrected = calibration.corrected(motion);
  EXPECT_DOUBLE_EQ(corrected.x, motion.x);
  EXPECT_DOUBLE_EQ(corrected.y, motion.y);
  EXPECT_DOUBLE_EQ(corrected.theta, motion.theta);
}

TEST(OdometryCalibration, LearnsTheDriftAndTurnScaleOfARealRobot) {
  // The Intel lab robot's, measured against the benchmark's reference: 0.06 rad/m, turns 4 % short.
  OdometryCalibration calibration;
  drive(calibration, 0.06, -0.04, 400);
  EXPECT_NEAR(calibration.drift_rad_per_m(), 0.06, 0.01);
  EXPECT_NEAR(calibration.turn_scale(), -0.04, 0.015);
  EXPECT_EQ(calibration.samples(), 400);
}

TEST(OdometryCalibration, ExactOdometryStaysUncorrected) {
  OdometryCalibration calibration;
  drive(calibration, 0.0, 0.0, 400);
  EXPECT_NEAR(calibration.drift_rad_per_m(), 0.0, 0.005);
  EXPECT_NEAR(calibration.turn_scale(), 0.0, 0.01);
  // What is left is the matches' noise, too small to be told apart from none: not applied.
  const Pose motion{0.4, 0.0, 0.3};
  EXPECT_DOUBLE_EQ(calibration.corrected(motion).theta, motion.theta);
}

TEST(OdometryCalibration, TheCorrectionTurnsTheChordByHalfTheHeadings) {
  OdometryCalibration calibration;
  drive(calibration, 0.1, 0.0, 600);
  const double drift = calibration.drift_rad_per_m();
  const Pose corrected = calibration.corrected(Pose{1.0, 0.0, 0.0});
  EXPECT_NEAR(corrected.theta, drift, 1e-12);
  EXPECT_NEAR(std::atan2(corrected.y, corrected.x), 0.5 * drift, 1e-12);
  EXPECT_NEAR(std::hypot(corrected.x, corrected.y), 1.0, 1e-12);  // the distance stays
}

TEST(OdometryCalibration, MatchesThatDoNotPinTheHeadingTeachNothing) {
  OdometryCalibration calibration;
  const double loose = 2.0 * OdometryCalibration::kMaxMatchSigma_rad;
  calibration.learn(Pose{0.4, 0.0, 0.0}, 0.05, loose * loose, kOdomVariance);
  calibration.learn(Pose{0.4, 0.0, 0.0}, std::nan(""), kMatchVariance, kOdomVariance);
  EXPECT_EQ(calibration.samples(), 0);
  EXPECT_DOUBLE_EQ(calibration.drift_rad_per_m(), 0.0);
}

TEST(OdometryCalibration, WrongMatchesCannotPushItBeyondWorkingOdometry) {
  OdometryCalibration calibration;
  for (int i = 0; i < 200; ++i) calibration.learn(Pose{0.4, 0.0, 0.3}, 1.0, kMatchVariance, kOdomVariance);
  EXPECT_LE(calibration.drift_rad_per_m(), OdometryCalibration::kMaxDrift_rad_per_m);
  EXPECT_LE(calibration.turn_scale(), OdometryCalibration::kMaxTurnScale);
}

}  // namespace
}  // namespace slam::correction

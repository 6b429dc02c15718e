#pragma once
// A robot's systematic odometry heading error, learned from its tracking matches and taken out of
// each odometry motion before it predicts the next keyframe. Wheel odometry turns too much or too
// little in a way that repeats: unequal wheel radii add a heading drift proportional to the distance
// driven, a wrong wheel base scales every turn. Real robots show it plainly (the Intel lab's robot
// drifts 0.06 rad per metre, a few degrees each metre, the same over the whole 45-minute log), and
// a robot with few points a keyframe cannot match its way out of it: its corridors came out curved.
// Model: true turn = odometry turn x (1 + turn_scale) + drift_per_m x travel, both estimated by a
// two-state Kalman filter whose measurement is each well-pinned match's heading disagreement with
// the (calibrated) prediction.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "common/core/geometry.hpp"

namespace slam::correction {

class OdometryCalibration {
 public:
  // Bounds: no working odometry is off by more (beyond them the matches, not the wheels, are wrong).
  static constexpr double kMaxDrift_rad_per_m = 0.15;
  static constexpr double kMaxTurnScale = 0.2;
  // The prior: a new robot's odometry is taken as right, within these.
  static constexpr double kPriorDrift_rad_per_m = 0.05;
  static constexpr double kPriorTurnScale = 0.05;
  // How fast the error may change (a tyre wears, a load shifts): variance added per keyframe.
  static constexpr double kDriftWander = 1e-7;
  static constexpr double kTurnScaleWander = 1e-7;
  // A match whose heading is pinned worse than this (a corridor's end, a ring) teaches nothing.
  static constexpr double kMaxMatchSigma_rad = 0.08;
  static constexpr double kSignificance = 3.0;

  OdometryCalibration() {
    covariance_.setZero();
    covariance_(0, 0) = kPriorDrift_rad_per_m * kPriorDrift_rad_per_m;
    covariance_(1, 1) = kPriorTurnScale * kPriorTurnScale;
  }

  // The odometry motion between two keyframes with the learned error taken out. The heading drifts
  // evenly along the motion, so its chord turns by half the heading's correction.
  Pose corrected(const Pose& odom_motion) const {
    const double dtheta = applied_turn(odom_motion);
    const double c = std::cos(0.5 * dtheta);
    const double s = std::sin(0.5 * dtheta);
    return Pose{c * odom_motion.x - s * odom_motion.y, s * odom_motion.x + c * odom_motion.y,
                wrap_angle(odom_motion.theta + dtheta)};
  }

  // A tracking match of a keyframe `odom_motion` after its predecessor disagreed with the heading
  // predicted from corrected(odom_motion) by `heading_innovation` (rad); the noise of that
  // disagreement is the match's heading variance plus the odometry's own.
  void learn(const Pose& odom_motion, double heading_innovation, double match_variance,
             double odom_variance) {
    if (!(match_variance >= 0.0) || match_variance > kMaxMatchSigma_rad * kMaxMatchSigma_rad) return;
    const double noise = match_variance + odom_variance;
    if (!(noise > 0.0) || !std::isfinite(heading_innovation)) return;
    covariance_(0, 0) += kDriftWander;
    covariance_(1, 1) += kTurnScaleWander;
    const Eigen::Vector2d h(std::hypot(odom_motion.x, odom_motion.y), wrap_angle(odom_motion.theta));
    // The disagreement with the whole estimate, of which the prediction applied only the significant part.
    heading_innovation -= h.x() * drift_ + h.y() * turn_scale_ - applied_turn(odom_motion);
    const double s = h.dot(covariance_ * h) + noise;
    const Eigen::Vector2d gain = covariance_ * h / s;
    drift_ = std::clamp(drift_ + gain.x() * heading_innovation, -kMaxDrift_rad_per_m, kMaxDrift_rad_per_m);
    turn_scale_ = std::clamp(turn_scale_ + gain.y() * heading_innovation, -kMaxTurnScale, kMaxTurnScale);
    covariance_ -= gain * h.transpose() * covariance_;
    ++samples_;
  }

  // The estimates, whether or not they are applied yet.
  double drift_rad_per_m() const { return drift_; }
  double turn_scale() const { return turn_scale_; }
  int samples() const { return samples_; }

 private:
  // An error not yet told apart from the matches' noise (within kSignificance sigmas of none) is
  // not applied: exact odometry would otherwise follow every keyframe's match noise.
  static double significant(double estimate, double variance) {
    return estimate * estimate > kSignificance * kSignificance * variance ? estimate : 0.0;
  }
  double applied_turn(const Pose& odom_motion) const {
    return significant(drift_, covariance_(0, 0)) * std::hypot(odom_motion.x, odom_motion.y) +
           significant(turn_scale_, covariance_(1, 1)) * wrap_angle(odom_motion.theta);
  }

  double drift_ = 0.0;
  double turn_scale_ = 0.0;
  Eigen::Matrix2d covariance_;
  int samples_ = 0;
};

}  // namespace slam::correction

#pragma once
// How far one robot's odometry can be trusted, learned from how much its tracking matches disagree
// with it. The corrector's odometry covariance is a nominal model (a little above the usual drift);
// a robot whose odometry is exact would be pulled about by every keyframe's match noise under it,
// and one that drifts three times as much would be followed with a lag. The trust is a scale on the
// nominal covariance, position and heading apart: the running mean of each well-pinned match's
// squared disagreement with the odometry prediction over the nominal variance of that motion.
// Match noise is left in the disagreement, so the scale errs towards distrusting odometry.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace slam::correction {

class OdometryTrust {
 public:
  // Bounds of the scale: odometry is never taken as exact (at 0.02 its sigma is a seventh of the
  // nominal one, below a sparse keyframe's match noise) nor dismissed (at 10, three times it).
  static constexpr double kMinScale = 0.02;
  static constexpr double kMaxScale = 10.0;
  // Weight of one keyframe in the running mean: about the last ten keyframes (4 m of travel).
  static constexpr double kRate = 0.1;
  // A match spread as wide as the tracking window along some direction (a corridor, a ring) does
  // not tell odometry error from match error there and teaches nothing (the corrector also leaves
  // out matches with a flat direction). A narrower spread stays in: its noise errs towards distrust.
  static constexpr double kMaxMatchSigma_m = 0.15;
  static constexpr double kMaxMatchSigma_rad = 0.08;

  // A tracking match that differs from the odometry prediction by `innovation` (x, y, theta; the
  // prediction being the previous keyframe's estimate moved by the odometry since), with the
  // match's covariance and the nominal odometry covariance of that motion.
  void learn(const Eigen::Vector3d& innovation, const Eigen::Matrix3d& match_cov,
             const Eigen::Matrix3d& nominal_odom_cov) {
    if (match_cov(0, 0) > kMaxMatchSigma_m * kMaxMatchSigma_m ||
        match_cov(1, 1) > kMaxMatchSigma_m * kMaxMatchSigma_m ||
        match_cov(2, 2) > kMaxMatchSigma_rad * kMaxMatchSigma_rad)
      return;
    const double linear_variance = nominal_odom_cov(0, 0) + nominal_odom_cov(1, 1);
    const double angular_variance = nominal_odom_cov(2, 2);
    if (!(linear_variance > 0.0) || !(angular_variance > 0.0)) return;
    linear_ = step(linear_, innovation.head<2>().squaredNorm() / linear_variance);
    angular_ = step(angular_, innovation.z() * innovation.z() / angular_variance);
    ++samples_;
  }

  // The nominal covariance of a motion scaled by what this robot's odometry has shown.
  Eigen::Matrix3d scaled(const Eigen::Matrix3d& nominal) const {
    const Eigen::Vector3d sigma_scale(std::sqrt(linear_), std::sqrt(linear_), std::sqrt(angular_));
    return sigma_scale.asDiagonal() * nominal * sigma_scale.asDiagonal();
  }

  double linear_scale() const { return linear_; }
  double angular_scale() const { return angular_; }
  int samples() const { return samples_; }

 private:
  static double step(double scale, double sample) {
    return scale + kRate * (std::clamp(sample, kMinScale, kMaxScale) - scale);
  }

  double linear_ = 1.0;  // a new robot's odometry is as good as the nominal model says
  double angular_ = 1.0;
  int samples_ = 0;
};

}  // namespace slam::correction

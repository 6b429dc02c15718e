#pragma once
// Gaussian pose estimates as PoseCorrector uses them: diagonal covariances, a floor against
// over-confidence, and the fusion of two estimates of one pose. Internal to the library.
#include <Eigen/Core>
#include <Eigen/LU>

#include "common/core/geometry.hpp"

namespace slam::correction {

inline Eigen::Matrix3d diagonal(double sx, double sy, double st) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  m(0, 0) = sx * sx;
  m(1, 1) = sy * sy;
  m(2, 2) = st * st;
  return m;
}

// A symmetric positive-definite covariance with a floor, so an over-confident match cannot make
// the graph stiff and a degenerate one cannot make it singular.
inline Eigen::Matrix3d with_floor(const Eigen::Matrix3d& c, double sigma_m, double sigma_rad) {
  Eigen::Matrix3d out = 0.5 * (c + c.transpose());
  out += diagonal(sigma_m, sigma_m, sigma_rad);
  return out;
}

// The information-weighted mean of two estimates of one pose (angles compared wrapped).
inline Pose fuse(const Pose& a, const Eigen::Matrix3d& ca, const Pose& b, const Eigen::Matrix3d& cb) {
  const Eigen::Matrix3d gain = ca * (ca + cb).inverse();
  const Eigen::Vector3d delta(b.x - a.x, b.y - a.y, wrap_angle(b.theta - a.theta));
  const Eigen::Vector3d step = gain * delta;
  return {a.x + step.x(), a.y + step.y(), wrap_angle(a.theta + step.z())};
}

inline Eigen::Matrix3d fused_covariance(const Eigen::Matrix3d& ca, const Eigen::Matrix3d& cb) {
  return (ca.inverse() + cb.inverse()).inverse();
}

// An accumulated uncertainty after one more odometry step of `length_m` with covariance `step`: the
// step's own noise, and the heading uncertainty swinging the position over the step's length.
inline void grow_by_motion(Eigen::Matrix3d& cov, const Eigen::Matrix3d& step, double length_m) {
  cov += step;
  const double swing = cov(2, 2) * length_m * length_m;
  cov(0, 0) += swing;
  cov(1, 1) += swing;
}

// After an odometry jump (a new segment) a robot's pose is barely known.
inline constexpr double kSegmentSigma_m = 2.0;
inline constexpr double kSegmentSigma_rad = 0.5;
// A robot's first keyframe: its start pose is trusted.
inline constexpr double kStartSigma_m = 0.05;
inline constexpr double kStartSigma_rad = 0.02;
// An operator's initial pose.
inline constexpr double kOperatorSigma_m = 0.02;
inline constexpr double kOperatorSigma_rad = 0.01;

}  // namespace slam::correction

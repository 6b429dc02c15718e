#pragma once
// Trajectory error against ground truth (absolute trajectory error, ATE): position errors of
// paired estimate/truth samples, and the rigid 2-D fit that aligns an estimate expressed in another
// frame (a robot's start frame, a map anchored elsewhere) with the truth before comparing.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::bench {

// Summary of a set of non-negative errors (metres).
struct ErrorStats {
  size_t count = 0;
  double mean = 0.0;
  double rmse = 0.0;
  double max = 0.0;
};

ErrorStats summarise(std::span<const double> errors);

// |estimate[i] - truth[i]| over the pairs (the spans must have the same length).
ErrorStats position_errors(std::span<const Vec2> estimate, std::span<const Vec2> truth);

// The rotation and translation (no scale) T minimising sum |T(estimate[i]) - truth[i]|^2, the
// 2-D case of the Kabsch/Umeyama fit, returned as the pose truth <- estimate. Fewer than two pairs,
// or all estimates on one point, give the translation of the centroids only.
Pose fit_rigid(std::span<const Vec2> estimate, std::span<const Vec2> truth);

// Every point moved by `transform`.
std::vector<Vec2> transformed(const Pose& transform, std::span<const Vec2> points);

// One ground-truth instant of one robot: where it was, where its odometry said it was (its own
// frame), and where the server put it (map frame).
struct TrajectorySample {
  std::string robot_id;
  Vec2 truth;
  Vec2 raw;
  Vec2 corrected;
};

struct TrajectoryErrors {
  ErrorStats corrected;
  ErrorStats raw;
  Pose alignment;  // world <- map applied to the corrected poses (identity when not aligned)
};

// ATE of the corrected and the raw poses. With `align`, the corrected poses of all robots get one
// rigid fit (they share the map frame) and each robot's raw poses their own (each robot has its
// own odometry frame); without, both are compared as they are (world-frame runs).
TrajectoryErrors trajectory_errors(std::span<const TrajectorySample> samples, bool align);

}  // namespace slam::bench

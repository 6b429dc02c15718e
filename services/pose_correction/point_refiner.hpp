#pragma once
// Refines a matched keyframe pose against the raw points of the keyframes around it, point to line:
// each keyframe point is pulled onto the line through the reference points within reach of it
// (Gauss-Newton, a Huber weight, the grid match as prior), re-associating every iteration.
//
// Why: the correlative search reads an occupancy grid, which holds a wall only as whole cells. A
// wall on a cell edge is drawn in the cell on one side of it or the other, depending on which rays
// cleared which cell, so a match against it is up to half a cell off and tracking pulls every
// robot by that much. The points keep the wall where it was measured.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::correction {

struct PointRefineOptions {
  double reach_m = 0.15;               // reference points within this of a keyframe point give its line
  int min_line_points = 4;             // fewer within reach: no line there
  double max_line_thickness_m = 0.02;  // RMS across the line above this: a corner or clutter
  double min_line_length_m = 0.025;    // RMS along it below this: too few points to give a direction
  double point_sigma_m = 0.015;        // a point's distance from its line (noise of both scans)
  double huber_m = 0.03;               // residuals beyond this weigh less (a wall seen past its end)
  int iterations = 6;
  double min_inlier_share = 0.5;  // of the keyframe's points that must find a line
  // The search found the pose to a cell and a step of heading. A larger move is a wrong association;
  // a turn beyond half a step (0.0125 rad at 4 m) is the heading of the robot's own recent trail,
  // which the points of a drifting robot would otherwise hold it to, even on a map known beforehand
  // (docs/mapping-quality.md). Either way the grid's result is kept.
  double max_shift_m = 0.075;
  double max_turn_rad = 0.006;
};

struct PointRefinement {
  Pose pose;
  int inliers = 0;  // keyframe points that found a line at `pose`
};

class PointRefiner {
 public:
  explicit PointRefiner(const PointRefineOptions& options = {}) : options_(options) {}

  // The reference points (map frame), binned for the nearest-line lookups. Reused between
  // keyframes: nothing is allocated once the buffers have grown.
  void set_reference(std::span<const Vec2> points);
  size_t reference_size() const { return points_.size(); }

  // The pose near `start` at which `points` (keyframe frame) lie best on the reference's lines;
  // `start_cov` weighs the start as a prior, so a direction the lines do not pin (along a corridor)
  // stays where the search put it. Nothing when too few points find a line, or the pose would move
  // further than the search could have missed by.
  std::optional<PointRefinement> refine(std::span<const Vec2> points, const Pose& start,
                                        const Eigen::Matrix3d& start_cov) const;

 private:
  struct Line {
    Vec2 centre;
    Vec2 normal;
  };
  std::optional<Line> line_near(Vec2 q) const;

  PointRefineOptions options_;
  // Bins of reach_m: a point's line is read from its own bin and the eight around it.
  Vec2 origin_;
  int32_t columns_ = 0, rows_ = 0;
  std::vector<uint32_t> bin_start_;  // prefix sums: bin b holds points_[bin_start_[b], bin_start_[b + 1])
  std::vector<Vec2> points_;         // sorted by bin
  std::vector<uint32_t> bin_of_;     // scratch of set_reference
};

}  // namespace slam::correction

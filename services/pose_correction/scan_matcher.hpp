#pragma once
// Matches a keyframe (a few dozen obstacle points in the keyframe's own frame) against an occupancy
// grid near a predicted pose: a correlative brute-force search over x, y and theta on a smoothed
// likelihood field of the occupied cells, then a least-squares refinement (Ceres) of the best
// candidate. The covariance comes from the spread of the well-scoring candidates, so an ambiguous
// match (a corridor, one wall) reports a large uncertainty along the ambiguous direction.
#include <Eigen/Core>
#include <cstdint>
#include <span>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "pose_correction/grid_view.hpp"

namespace slam::correction {

struct SearchWindow {
  double linear_m = 0.15;     // +- around the prediction in x and y
  double angular_rad = 0.08;  // +- around the predicted heading
};

struct MatcherOptions {
  double linear_step_m = 0.0;   // 0: the grid's resolution
  double angular_step_rad = 0.0;  // 0: chosen so the farthest point moves about one cell per step
  double field_sigma_m = 0.05;  // blur of the likelihood field around occupied cells
  int min_points = 12;          // fewer points: not matchable
  double min_score = 0.45;      // mean likelihood (0..1) of the points at the best pose
};

struct MatchResult {
  Pose pose;                    // the keyframe's pose in the grid's frame
  Eigen::Matrix3d covariance;   // of (x, y, theta)
  double score = 0.0;           // mean likelihood of the points at `pose`, 0..1
  int points_used = 0;          // points that fell inside the grid
};

class ScanMatcher {
 public:
  explicit ScanMatcher(const MatcherOptions& options = {});

  // Errors (as values): too few points, the window leaves the grid entirely, best score below
  // min_score. Reuses internal buffers: allocation-free after warm-up for same-sized windows.
  Result<MatchResult> match(const GridView& grid, std::span<const Vec2> points, const Pose& predicted,
                            const SearchWindow& window);

 private:
  MatcherOptions options_;
  // implementation-defined buffers (likelihood field window, rotated points)
};

}  // namespace slam::correction

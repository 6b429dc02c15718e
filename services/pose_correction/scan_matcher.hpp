#pragma once
// Matches a keyframe (a few dozen obstacle points in the keyframe's own frame) against an occupancy
// grid near a predicted pose: a correlative brute-force search over x, y and theta on a smoothed
// likelihood field of the occupied cells, then a least-squares refinement (Ceres) of the best
// candidate. The covariance comes from the spread of the well-scoring candidates, so an ambiguous
// match (a corridor, one wall) reports a large uncertainty along the ambiguous direction.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "pose_correction/grid_view.hpp"

namespace slam::correction {

struct SearchWindow {
  double linear_m = 0.15;     // +- around the prediction in x and y
  double angular_rad = 0.08;  // +- around the predicted heading
};

struct MatcherOptions {
  double linear_step_m = 0.0;     // 0: the grid's resolution (rounded to whole cells)
  double angular_step_rad = 0.0;  // 0: chosen so the farthest point moves about one cell per step
  double field_sigma_m = 0.05;    // blur of the likelihood field around occupied cells
  int min_points = 12;            // fewer points: not matchable
  double min_score = 0.45;        // mean likelihood (0..1) of the points at the best pose
  // How sharply the covariance weighs candidates: a candidate whose summed likelihood lies this much
  // below the best one's weighs e^-1 of it (Olson's probabilistic reading of the score map).
  double covariance_temperature = 1.0;
  int refine_iterations = 10;  // Ceres iterations of the least-squares refinement
};

struct MatchResult {
  Pose pose;                   // the keyframe's pose in the grid's frame
  Eigen::Matrix3d covariance;  // of (x, y, theta)
  double score = 0.0;          // mean likelihood of the points at `pose`, 0..1
  int points_used = 0;         // points that fell inside the grid
};

class ScanMatcher {
 public:
  explicit ScanMatcher(const MatcherOptions& options = {});

  // `points` are in the keyframe's own frame; `predicted` is the keyframe's pose in the grid's frame.
  // Errors (as values): too few points, an empty grid view, a window that lies entirely off the
  // grid, non-finite input, best score below min_score.
  Result<MatchResult> match(const GridView& grid, std::span<const Vec2> points, const Pose& predicted,
                            const SearchWindow& window);

 private:
  MatcherOptions options_;
  // Reused between matches, so the search allocates nothing once they have grown to the largest
  // window seen (the Ceres refinement still builds its small problem per match).
  std::vector<float> kernel_;     // likelihood by cell offset from an occupied cell
  int kernel_radius_ = 0;         // cells; kernel_ is (2r + 1)^2
  double kernel_resolution_ = 0;  // resolution kernel_ was built for
  std::vector<float> field_;      // likelihood at the cell centres of field_box_, row-major
  CellBox field_box_;             // in grid cells
  std::vector<int32_t> lookup_;   // per point: field_ index of its cell at the current heading
  std::vector<float> sums_;       // per candidate (heading, y, x): summed likelihood
};

}  // namespace slam::correction

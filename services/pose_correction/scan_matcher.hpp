#pragma once
// Matches a keyframe (a few dozen obstacle points, or a laser scan, in the keyframe's own frame)
// against an occupancy grid near a predicted pose, in four steps each in its own unit: the
// likelihood field of the occupied cells (likelihood_field), a correlative search over x, y and
// theta (correlative_search), the uncertainty read from the whole search response
// (response_spread: a corridor, one wall or a ring reports a large or flat spread, a second good peak
// an `ambiguity`), and a least-squares refinement of the best candidate (field_refinement, Ceres).
// Among equally good candidates the one nearest the prediction is taken.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "pose_correction/correlative_search.hpp"
#include "pose_correction/grid_view.hpp"
#include "pose_correction/likelihood_field.hpp"

namespace slam::correction {

struct MatcherOptions {
  double linear_step_m = 0.0;     // 0: the grid's resolution (rounded to whole cells)
  double angular_step_rad = 0.0;  // 0: chosen so the farthest point moves about one cell per step
  double field_sigma_m = 0.05;    // blur of the likelihood field around occupied cells
  int min_points = 12;            // fewer points: not matchable
  double min_score = 0.45;        // mean likelihood (0..1) of the points at the best pose
  // The points of a keyframe are not independent observations: they share its own small drift, the
  // map's blur and the grid's cells. Each candidate's summed likelihood is read as a log-likelihood
  // (Olson's probabilistic reading of the score map) of this many independent points, so a candidate
  // whose mean likelihood lies 1 / independent_points below the best weighs e^-1 of it. 20 (about two
  // per v1 message): a ring's or a corridor's ridge, which runs between the lattice's cells, stays
  // in the covariance, while a room's peak stays within a cell and about a degree; 40 loses the ridge.
  double independent_points = 20.0;
  // A candidate this far from the best one (metres, with heading counted as the arc it swings at
  // the points' RMS range) belongs to another peak; the best such candidate gives `ambiguity`.
  double distinct_separation_m = 0.2;
  int refine_iterations = 10;  // Ceres iterations of the least-squares refinement
};

struct MatchResult {
  Pose pose;                   // the keyframe's pose in the grid's frame
  Eigen::Matrix3d covariance;  // of (x, y, theta); a flat direction: the window's uniform spread
  double score = 0.0;          // mean likelihood of the points at `pose`, 0..1
  int points_used = 0;         // points that fell inside the grid
  // Directions (of x, y, theta) along which the response stayed flat to the window's edge: the map
  // does not pin the pose there (a corridor along its length, a ring around its centre).
  int flat_directions = 0;
  // Summed likelihood of the best candidate at least distinct_separation_m from the best, relative
  // to the best's (0..1; 0 when the window holds no such candidate). Near 1: a second peak (or a
  // ridge) as good as the best, so the best is a guess among equals.
  double ambiguity = 0.0;
  // The best candidate lies on the search window's edge (in x, y or heading): the response may
  // still rise beyond it, so the best is not known to be a peak.
  bool at_window_edge = false;
};

// Whether a match pins one pose, as a loop closure must (a wrong closure is worse than none): no
// flat direction, no second peak or ridge scoring close to the best away from it (a ring, a corridor,
// look-alike rooms within the window), a small spread, and a best candidate inside the window.
struct DistinctMatch {
  double max_ambiguity = 0.8;
  double max_sigma_m = 0.05;
  double max_sigma_rad = 0.035;
  bool accepts(const MatchResult& match) const;
};

class ScanMatcher {
 public:
  explicit ScanMatcher(const MatcherOptions& options = {});

  // `points` are in the keyframe's own frame; `predicted` is the keyframe's pose in the grid's frame.
  // Errors (as values): too few points, an empty grid view, a window that lies entirely off the
  // grid, non-finite input, best score below min_score.
  // `independent_points` > 0 replaces MatcherOptions::independent_points for this match (a laser
  // scan's points are far more independent than a sparse robot's gathered over half a metre).
  Result<MatchResult> match(const GridView& grid, std::span<const Vec2> points, const Pose& predicted,
                            const SearchWindow& window, double independent_points = 0.0);

 private:
  MatcherOptions options_;
  // Reused between matches, so the search allocates nothing once they have grown to the largest
  // window seen (the Ceres refinement still builds its small problem per match).
  LikelihoodField field_;
  CorrelativeSearch search_;
};

}  // namespace slam::correction

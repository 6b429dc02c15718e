#pragma once
// The uncertainty of a correlative search's best candidate, read from the whole response (Olson
// 2009): every candidate weighted by its likelihood relative to the best, read as a log-likelihood,
// gives a covariance; a direction whose spread reaches that of a window-wide flat response is not
// pinned by the map (a corridor along its length, a ring about its centre); the best candidate
// far from the best one measures a second peak.
#include <Eigen/Core>
#include <span>

#include "pose_correction/correlative_search.hpp"

namespace slam::correction {

struct ResponseSpread {
  Eigen::Matrix3d covariance;  // of (x, y, theta), floored at the search's own discretisation
  int flat_directions = 0;     // directions whose variance is the window's, not the map's
  double ambiguity = 0.0;      // best summed likelihood away from the best, relative to it (0..1)
};

struct SpreadInputs {
  std::span<const float> sums;  // per lattice candidate
  const SearchLattice* lattice = nullptr;
  size_t best = 0;                     // index of the best candidate
  double rms_range = 1.0;              // heading offsets count as the arc they swing at this range
  double temperature = 1.0;            // summed likelihood that weighs e^-1: points / independent points
  double distinct_separation_m = 0.2;  // a candidate this far from the best belongs to another peak
  double resolution = 0.05;            // of the grid, for the covariance's floor
};

ResponseSpread response_spread(const SpreadInputs& in);

}  // namespace slam::correction

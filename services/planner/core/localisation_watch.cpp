#include "planner/core/localisation_watch.hpp"

#include <cmath>

namespace slam::planner {

Status validate(const RelocaliseConfig& config) {
  if (!std::isfinite(config.return_sigma_m) || config.return_sigma_m < 0.0) {
    return Error{"explore.return_sigma_m must be a finite number >= 0 (0: off)"};
  }
  if (!std::isfinite(config.tied_sigma_m) || config.tied_sigma_m <= 0.0) {
    return Error{"explore.tied_sigma_m must be positive"};
  }
  if (config.return_sigma_m > 0.0 && config.tied_sigma_m >= config.return_sigma_m) {
    return Error{"explore.tied_sigma_m must be below explore.return_sigma_m"};
  }
  return Status::ok();
}

void LocalisationWatch::observe_uncertainty(double sigma_m, const RelocaliseConfig& config) {
  if (!std::isfinite(sigma_m) || sigma_m < 0.0) return;
  // Only a shrinking uncertainty shows a tie to the old map: a robot is also known well at its
  // trusted start, where there may be nothing old to tie to when it comes back.
  const bool shrunk = std::isfinite(sigma_m_) && sigma_m < sigma_m_;
  sigma_m_ = sigma_m;
  if (!tied(config) || !shrunk || !position_) return;
  returned_ = false;
  tied_place_ = position_;
}

void LocalisationWatch::observe_position(Vec2 position, const RelocaliseConfig& config) {
  if (!std::isfinite(position.x) || !std::isfinite(position.y)) return;
  position_ = position;
  // Still tied since the last tie: the place to return to moves along with the robot.
  if (tied_place_ && tied(config)) tied_place_ = position;
}

std::optional<Vec2> LocalisationWatch::take_return(const RelocaliseConfig& config) {
  if (config.return_sigma_m <= 0.0 || returned_ || !tied_place_ || !std::isfinite(sigma_m_) ||
      sigma_m_ <= config.return_sigma_m) {
    return std::nullopt;
  }
  returned_ = true;
  return tied_place_;
}

}  // namespace slam::planner

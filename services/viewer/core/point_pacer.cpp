// Step sizing for the point texture's re-render (see point_pacer.hpp).
#include "viewer/core/point_pacer.hpp"

#include <algorithm>
#include <cmath>

namespace slam::viewer {
namespace {

// How far one frame moves the estimates. A slower step weighs more (the next frame must not
// overrun) but not fully, so one stall from another process does not halve the next step; a
// faster step weighs less, so one lucky frame does not double the next.
constexpr double kSlowerWeight = 0.5;
constexpr double kFasterWeight = 0.25;
constexpr double kBaseWeight = 0.2;
// A step is at most this many times the last measured one: a cost estimate that is too low (a
// frame that happened to be quicker than the base) cannot make one step a hundred times larger.
constexpr double kMaxGrowth = 2.0;

}  // namespace

Status validate(const PacerConfig& c) {
  if (!(c.frame_ms > 0.0) || !std::isfinite(c.frame_ms)) return Error{"target frame time must be positive"};
  if (c.min_points == 0) return Error{"minimum points per step must be positive"};
  if (c.max_points < c.min_points) return Error{"maximum points per step is below the minimum"};
  if (c.first_points < c.min_points || c.first_points > c.max_points)
    return Error{"first step's points must lie between the minimum and the maximum"};
  return {};
}

PointPacer::PointPacer(const PacerConfig& config) : config_(config), budget_(config.first_points) {}

void PointPacer::record(uint64_t points, double ms) {
  if (!(ms >= 0.0) || !std::isfinite(ms)) return;
  if (points < config_.min_points) {
    base_ms_ = have_base_ ? base_ms_ + kBaseWeight * (ms - base_ms_) : ms;
    have_base_ = true;
  } else {
    const double measured = std::max(0.0, ms - base_ms_) / static_cast<double>(points);
    if (!have_cost_)
      ms_per_point_ = measured;
    else
      ms_per_point_ +=
          (measured > ms_per_point_ ? kSlowerWeight : kFasterWeight) * (measured - ms_per_point_);
    have_cost_ = true;
    last_step_points_ = points;
  }
  update_budget();
}

void PointPacer::update_budget() {
  if (!have_cost_) return;
  const double room = config_.frame_ms - base_ms_;
  double fits = kMaxGrowth * static_cast<double>(last_step_points_);
  if (room <= 0.0)
    fits = 0.0;
  else if (ms_per_point_ > 0.0)
    fits = std::min(fits, room / ms_per_point_);
  budget_ = static_cast<uint64_t>(
      std::clamp(fits, static_cast<double>(config_.min_points), static_cast<double>(config_.max_points)));
}

}  // namespace slam::viewer

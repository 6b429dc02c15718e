// GoalTracker transitions. Direct and Square drive straight lines by design (the square is a
// calibration drive); Planned, Home and Explore follow planned paths and re-plan.
#include "planner/core/goal_tracker.hpp"

#include <cmath>
#include <utility>

#include "common/core/square_path.hpp"
#include "planner/core/line_of_sight.hpp"

namespace slam::planner {

Status validate(const Goal& goal) {
  if (!std::isfinite(goal.target.x) || !std::isfinite(goal.target.y)) {
    return Error{"goal target is not finite"};
  }
  if (goal.mode == GoalMode::Square && (!std::isfinite(goal.square_size) || goal.square_size <= 0.0)) {
    return Error{"square goal needs a positive, finite square_size"};
  }
  return Status::ok();
}

Status validate(const TrackerConfig& config) {
  if (!std::isfinite(config.reach_tolerance_m) || config.reach_tolerance_m <= 0.0) {
    return Error{"goals.reach_tolerance_m must be positive"};
  }
  if (!std::isfinite(config.stray_threshold_m) || config.stray_threshold_m <= 0.0) {
    return Error{"goals.stray_threshold_m must be positive"};
  }
  if (!std::isfinite(config.resend_period_s) || config.resend_period_s <= 0.0) {
    return Error{"goals.resend_period_s must be positive"};
  }
  return Status::ok();
}

std::vector<Vec2> square_path(Vec2 target, double size, SquareAnchor anchor) {
  const auto c = square_corners(target, size, anchor == SquareAnchor::Centred);
  return {c[0], c[1], c[2], c[3], c[0]};
}

bool GoalTracker::plans_paths() const {
  return goal_.mode == GoalMode::Planned || goal_.mode == GoalMode::Home || goal_.mode == GoalMode::Explore;
}

void GoalTracker::set_goal(const Goal& goal, Vec2 position, Vec2 home) {
  goal_ = goal;
  home_ = home;
  position_ = position;
  reason_.clear();
  waypoints_.clear();
  current_ = 0;
  plan_wanted_ = false;
  frontier_set_ = false;
  revisiting_ = false;
  homing_ = false;
  reached_frontier_.reset();
  target_ = goal.target;
  status_ = GoalStatus::Active;
  switch (goal.mode) {
    case GoalMode::Idle:
      status_ = GoalStatus::None;
      break;
    case GoalMode::Direct:
      follow({goal.target}, position);
      break;
    case GoalMode::Square:
      follow(square_path(goal.target, goal.square_size, goal.square_anchor), position);
      break;
    case GoalMode::Planned:
      plan_wanted_ = true;
      break;
    case GoalMode::Home:
      target_ = home;
      plan_wanted_ = true;
      break;
    case GoalMode::Explore:
      target_ = position;
      break;
    case GoalMode::Stop:
      // Holding is the goal itself: it is reached at once and the position keeps being sent.
      target_ = position;
      waypoints_ = {position};
      leg_start_ = position;
      status_ = GoalStatus::Reached;
      break;
  }
  ++waypoint_seq_;
  ++revision_;
}

void GoalTracker::follow(std::vector<Vec2> waypoints, Vec2 from) {
  waypoints_ = std::move(waypoints);
  current_ = 0;
  leg_start_ = from;
  plan_wanted_ = false;
  ++waypoint_seq_;
  ++revision_;
  update_position(position_);
}

void GoalTracker::update_position(Vec2 position) {
  position_ = position;
  if (status_ != GoalStatus::Active || waypoints_.empty() || current_ >= waypoints_.size()) return;
  bool advanced = false;
  while (current_ < waypoints_.size() &&
         distance(position, waypoints_[current_]) <= config_.reach_tolerance_m) {
    leg_start_ = waypoints_[current_];
    ++current_;
    advanced = true;
  }
  if (advanced) {
    ++waypoint_seq_;
    ++revision_;
  }
  if (current_ >= waypoints_.size()) {
    finish_route();
    return;
  }
  if (plans_paths() && !plan_wanted_ &&
      distance_to_segment(position, leg_start_, waypoints_[current_]) > config_.stray_threshold_m) {
    plan_wanted_ = true;
  }
}

void GoalTracker::finish_route() {
  if (goal_.mode == GoalMode::Explore && !homing_) {
    if (frontier_set_) reached_frontier_ = target_;
    drop_frontier();
    return;
  }
  status_ = GoalStatus::Reached;
  ++revision_;
}

void GoalTracker::check_path(const PlanningGrid& grid, UnknownPolicy policy) {
  if (status_ != GoalStatus::Active || !plans_paths() || plan_wanted_ || waypoints_.empty() ||
      current_ >= waypoints_.size()) {
    return;
  }
  // From the leg's start, not the robot: a robot brushing an inflated cell must not fail its plan.
  // The current leg may begin inside impassable cells (an escape leg, or a wall inflated under a
  // waypoint already reached): only where it leads counts.
  Vec2 from = leg_start_;
  for (size_t i = current_; i < waypoints_.size(); ++i) {
    const bool clear = i == current_ ? segment_clear_leaving(grid, from, waypoints_[i], policy)
                                     : segment_clear(grid, from, waypoints_[i], policy);
    if (!clear) {
      plan_wanted_ = true;
      return;
    }
    from = waypoints_[i];
  }
}

void GoalTracker::set_path(const std::vector<Vec2>& path) {
  if (status_ != GoalStatus::Active || !plans_paths() || path.empty()) return;
  follow(std::vector<Vec2>(path.begin() + 1, path.end()), path.front());
  if (waypoints_.empty()) finish_route();
}

void GoalTracker::plan_failed(const std::string& reason) {
  if (goal_.mode == GoalMode::Explore && !homing_) {
    drop_frontier();
    return;
  }
  fail(reason);
}

void GoalTracker::fail(const std::string& reason) {
  status_ = GoalStatus::Failed;
  reason_ = reason;
  plan_wanted_ = false;
  ++revision_;
}

bool GoalTracker::wants_frontier() const {
  return goal_.mode == GoalMode::Explore && status_ == GoalStatus::Active && !homing_ && !frontier_set_ &&
         !revisiting_;
}

void GoalTracker::set_frontier(Vec2 target) {
  if (!wants_frontier()) return;
  target_ = target;
  frontier_set_ = true;
  plan_wanted_ = true;
  ++revision_;
}

void GoalTracker::new_route(Vec2 target, bool plan) {
  waypoints_.clear();
  current_ = 0;
  target_ = target;
  plan_wanted_ = plan;
  ++waypoint_seq_;
  ++revision_;
}

void GoalTracker::drop_frontier() {
  if (goal_.mode != GoalMode::Explore || homing_) return;
  frontier_set_ = false;
  revisiting_ = false;
  new_route(position_, false);
}

void GoalTracker::revisit(Vec2 place) {
  if (goal_.mode != GoalMode::Explore || status_ != GoalStatus::Active || homing_) return;
  frontier_set_ = false;
  revisiting_ = true;
  new_route(place, true);
}

std::optional<Vec2> GoalTracker::take_reached_frontier() {
  return std::exchange(reached_frontier_, std::nullopt);
}

void GoalTracker::exploration_complete() {
  if (goal_.mode != GoalMode::Explore || status_ != GoalStatus::Active || homing_) return;
  homing_ = true;
  frontier_set_ = false;
  revisiting_ = false;
  new_route(home_, true);
}

void GoalTracker::take_over() {
  // An exploring robot without a frontier asks for one instead (wants_frontier()).
  if (status_ == GoalStatus::Active && plans_paths() && !wants_frontier()) plan_wanted_ = true;
  sent_once_ = false;
  ++revision_;
}

std::optional<Vec2> GoalTracker::current_waypoint() const {
  if (waypoints_.empty()) return std::nullopt;
  return current_ < waypoints_.size() ? waypoints_[current_] : waypoints_.back();
}

std::span<const Vec2> GoalTracker::remaining() const {
  if (current_ >= waypoints_.size()) return {};
  return std::span<const Vec2>(waypoints_).subspan(current_);
}

bool GoalTracker::should_send(int64_t now_ns) {
  const bool holding = goal_.mode == GoalMode::Stop;
  if (!holding && (status_ != GoalStatus::Active || current_ >= waypoints_.size())) return false;
  if (waypoints_.empty()) return false;
  const bool changed = !sent_once_ || sent_seq_ != waypoint_seq_;
  const bool due = static_cast<double>(now_ns - last_sent_ns_) >= config_.resend_period_s * 1e9;
  if (!changed && !due) return false;
  sent_once_ = true;
  sent_seq_ = waypoint_seq_;
  last_sent_ns_ = now_ns;
  return true;
}

}  // namespace slam::planner

#pragma once
// One robot's standing goal as a pure state machine: which waypoint it drives to now, when it has
// arrived, when its path needs planning again and when the waypoint must be (re)sent. Time is
// passed in, never read, so tests drive it step by step.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/core/fleet_messages.hpp"
#include "common/core/result.hpp"
#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

using msg::GoalMode;
using msg::GoalStatus;
using msg::SquareAnchor;

struct Goal {
  uint64_t goal_id = 0;
  GoalMode mode = GoalMode::Idle;
  Vec2 target;
  double square_size = 0.0;  // metres, Square only
  SquareAnchor square_anchor = SquareAnchor::Corner;
};

// Ok, or what is wrong with the goal (non-finite target, bad square size).
Status validate(const Goal& goal);

// The square path's waypoints: common/square_path.hpp's corners, closing back at the first.
std::vector<Vec2> square_path(Vec2 target, double size, SquareAnchor anchor);

struct TrackerConfig {
  double reach_tolerance_m = 0.15;  // a waypoint this close counts as reached
  double stray_threshold_m = 0.75;  // further than this off the path segment: re-plan
  double resend_period_s = 1.0;     // legacy robots have no acknowledgement: repeat this often
};

Status validate(const TrackerConfig& config);

class GoalTracker {
 public:
  explicit GoalTracker(const TrackerConfig& config) : config_(config) {}

  // Starts `goal` for a robot now at `position`, first seen at `home`. The goal must be valid.
  void set_goal(const Goal& goal, Vec2 position, Vec2 home);
  // Advances past reached waypoints and flags a re-plan when the robot strays from its path.
  void update_position(Vec2 position);
  // After a grid change: re-plan when a remaining path segment is no longer clear.
  void check_path(const PlanningGrid& grid, UnknownPolicy policy);

  // Planned modes (Planned, Home, Explore once it has a target) ask for a path here.
  bool needs_plan() const { return status_ == GoalStatus::Active && plan_wanted_; }
  Vec2 plan_target() const { return target_; }
  // A plan from the robot's position to plan_target(): path[0] is the start, the rest waypoints.
  void set_path(const std::vector<Vec2>& path);
  // Planning failed: the goal fails (Explore instead drops the frontier and asks for another).
  void plan_failed(const std::string& reason);

  // Exploration: wants_frontier() while exploring without a frontier to drive to.
  bool wants_frontier() const;
  void set_frontier(Vec2 target);
  // Gives up the current frontier (reached, vanished, stalled, unreachable), or ends a revisit:
  // asks for another frontier.
  void drop_frontier();
  // An exploring robot drives back to `place` (ground it is localised on, LocalisationWatch)
  // instead of its frontier; arriving, or drop_frontier(), ends the revisit and it asks for a
  // frontier again. Only while exploring, not homing.
  void revisit(Vec2 place);
  bool revisiting() const { return revisiting_; }
  // The target is a place the robot stood on (home, a revisit): inflation may cover it now, and a
  // cell beside it will do.
  bool target_stood_on() const { return goal_.mode == GoalMode::Home || homing_ || revisiting_; }
  bool has_frontier() const { return mode() == GoalMode::Explore && !homing_ && frontier_set_; }
  // The frontier the robot last arrived at, once: still a frontier after the robot stood on it,
  // it cannot be seen from there and should not be handed out again.
  std::optional<Vec2> take_reached_frontier();
  // No frontier left for this robot: it drives home and the goal is reached there.
  void exploration_complete();
  // The robot comes under this planner from another one (several planners share the robots): a
  // path this tracker holds may be stale and the other planner's is unknown here, so a planned
  // route is planned again from where the robot is, and the current waypoint goes out at once.
  void take_over();

  // The waypoint to drive to now, if any.
  std::optional<Vec2> current_waypoint() const;
  // True when the current waypoint must go out at `now_ns`: it changed since the last send, or
  // resend_period_s has passed. Records the send. Only while Active, and always in Stop.
  bool should_send(int64_t now_ns);

  const Goal& goal() const { return goal_; }
  GoalMode mode() const { return goal_.mode; }
  GoalStatus status() const { return status_; }
  const std::string& reason() const { return reason_; }
  Vec2 target() const { return target_; }
  const std::vector<Vec2>& waypoints() const { return waypoints_; }
  size_t current_index() const { return current_; }
  std::span<const Vec2> remaining() const;
  // Where the current leg began: the previous waypoint, or where the path started.
  Vec2 leg_start() const { return leg_start_; }
  bool homing() const { return homing_; }
  // Bumped whenever waypoints, current index or status change: time to publish the path again.
  uint64_t revision() const { return revision_; }

 private:
  void follow(std::vector<Vec2> waypoints, Vec2 from);
  // Drops the waypoints for a route to `target`, planned when `plan` (else the robot holds).
  void new_route(Vec2 target, bool plan);
  void finish_route();
  void fail(const std::string& reason);
  bool plans_paths() const;

  TrackerConfig config_;
  Goal goal_;
  GoalStatus status_ = GoalStatus::None;
  std::string reason_;
  Vec2 target_;
  Vec2 home_;
  Vec2 position_;
  std::vector<Vec2> waypoints_;
  Vec2 leg_start_;  // where the current leg began: the previous waypoint or the start
  size_t current_ = 0;
  bool plan_wanted_ = false;
  bool frontier_set_ = false;
  bool revisiting_ = false;
  bool homing_ = false;
  std::optional<Vec2> reached_frontier_;
  uint64_t waypoint_seq_ = 0;  // bumped when the current waypoint changes
  uint64_t sent_seq_ = 0;
  bool sent_once_ = false;
  int64_t last_sent_ns_ = 0;
  uint64_t revision_ = 0;
};

}  // namespace slam::planner

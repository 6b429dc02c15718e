// Fleet orchestration: goal fan-out, planning, exploration, due waypoints.
#include "planner/fleet.hpp"

namespace slam::planner {

Status validate(const FleetConfig& config) {
  if (auto s = validate(config.goals); !s) return s;
  if (auto s = validate(config.explore); !s) return s;
  return validate(config.planner);
}

Fleet::Fleet(const FleetConfig& config) : config_(config), planner_(config.planner) {}

void Fleet::observe(const std::string& robot_id, Vec2 position) {
  auto [it, inserted] = robots_.try_emplace(
      robot_id, Robot{GoalTracker(config_.goals), position, position, ProgressWatch{}, 0});
  it->second.position = position;
  if (!inserted) it->second.tracker.update_position(position);
}

Status Fleet::set_goal(const std::string& robot_id, const Goal& goal) {
  if (auto s = validate(goal); !s) return s;
  auto start = [&](Robot& r) {
    r.tracker.set_goal(goal, r.position, r.home);
    if (goal.mode == GoalMode::Explore) exploration_complete_ = false;
  };
  if (robot_id == kAllRobots) {
    for (auto& [id, robot] : robots_) start(robot);
    return Status::ok();
  }
  auto it = robots_.find(robot_id);
  if (it == robots_.end()) return Error{"unknown robot '" + robot_id + "'"};
  start(it->second);
  return Status::ok();
}

void Fleet::grid_changed(const PlanningGrid& grid, std::optional<CellBox> box) {
  if (box) {
    frontiers_.update(grid, *box);
  } else {
    frontiers_.rebuild(grid);
  }
  for (auto& [id, robot] : robots_) robot.tracker.check_path(grid, config_.planner.unknown);
}

void Fleet::tick(const PlanningGrid& grid, int64_t now_ns) {
  if (grid.empty()) return;
  explore(grid, now_ns);
  plan_paths(grid);
  // A frontier that turned out unreachable was dropped by plan_paths: offer another at once.
  explore(grid, now_ns);
  plan_paths(grid);
}

void Fleet::plan_paths(const PlanningGrid& grid) {
  for (auto& [id, robot] : robots_) {
    GoalTracker& t = robot.tracker;
    if (!t.needs_plan()) continue;
    const PlanResult result = planner_.plan_astar(grid, robot.position, t.plan_target());
    if (result.ok()) {
      t.set_path(result.path);
    } else {
      if (t.has_frontier()) blacklist_.add(t.plan_target());
      t.plan_failed(std::string(to_string(result.status)) + ": " + result.reason);
    }
  }
}

void Fleet::explore(const PlanningGrid& grid, int64_t now_ns) {
  if (!frontiers_.matches(grid)) frontiers_.rebuild(grid);
  // Drop frontiers that vanished (explored by someone) or that the robot stopped approaching.
  for (auto& [id, robot] : robots_) {
    GoalTracker& t = robot.tracker;
    if (!t.has_frontier()) continue;
    const auto cell = grid.cell_at(t.plan_target());
    if (!cell || !frontiers_.is_frontier(*cell, grid)) {
      t.drop_frontier();
    } else if (robot.progress.stalled(robot.position, now_ns, config_.explore)) {
      blacklist_.add(t.plan_target());
      t.drop_frontier();
    }
  }
  std::vector<ExploringRobot> seekers;
  std::vector<std::string> ids;
  for (auto& [id, robot] : robots_) {
    if (!robot.tracker.wants_frontier()) continue;
    seekers.push_back(ExploringRobot{static_cast<uint32_t>(ids.size()), robot.position});
    ids.push_back(id);
  }
  if (seekers.empty()) return;

  frontiers_.cluster(grid, config_.explore.min_cluster_cells, clusters_);
  eligible_.assign(clusters_.size(), 1);
  for (size_t c = 0; c < clusters_.size(); ++c) {
    const Vec2 target = grid.centre(clusters_[c].target);
    if (blacklist_.contains(target, config_.explore.blacklist_radius_m)) eligible_[c] = 0;
    for (const auto& [id, robot] : robots_) {
      if (robot.tracker.has_frontier() &&
          distance(robot.tracker.plan_target(), target) <= config_.explore.blacklist_radius_m) {
        eligible_[c] = 0;
      }
    }
  }
  const auto cost = [&](Vec2 from, Vec2 to) -> std::optional<double> {
    const PlanResult r = planner_.plan_astar(grid, from, to);
    return r.ok() ? std::optional<double>(r.length_m) : std::nullopt;
  };
  const auto assignments =
      assign_frontiers(seekers, clusters_, eligible_, grid, config_.explore.gain_weight, cost);
  std::vector<bool> assigned(seekers.size(), false);
  for (const FrontierAssignment& a : assignments) {
    Robot& robot = robots_.at(ids[a.robot]);
    robot.tracker.set_frontier(a.target);
    robot.progress.start(a.target, robot.position, now_ns);
    assigned[a.robot] = true;
  }
  bool any_left = false;
  for (size_t c = 0; c < clusters_.size(); ++c) any_left = any_left || eligible_[c] != 0;
  for (size_t s = 0; s < seekers.size(); ++s) {
    if (assigned[s]) continue;
    // Nothing this robot can reach is left: its exploration is over.
    robots_.at(ids[s]).tracker.exploration_complete();
  }
  if (!any_left) exploration_complete_ = true;
}

void Fleet::due_waypoints(int64_t now_ns, std::vector<DueWaypoint>& out) {
  out.clear();
  for (auto& [id, robot] : robots_) {
    GoalTracker& t = robot.tracker;
    if (!t.should_send(now_ns)) continue;
    const auto wp = t.current_waypoint();
    if (!wp) continue;
    const auto rest = t.remaining();
    out.push_back(DueWaypoint{id, *wp, std::vector<Vec2>(rest.begin(), rest.end())});
  }
}

std::vector<std::string> Fleet::take_changed() {
  std::vector<std::string> out;
  for (auto& [id, robot] : robots_) {
    if (robot.tracker.revision() == robot.published_revision) continue;
    robot.published_revision = robot.tracker.revision();
    out.push_back(id);
  }
  return out;
}

const GoalTracker* Fleet::tracker(const std::string& robot_id) const {
  auto it = robots_.find(robot_id);
  return it == robots_.end() ? nullptr : &it->second.tracker;
}

std::optional<Vec2> Fleet::home(const std::string& robot_id) const {
  auto it = robots_.find(robot_id);
  return it == robots_.end() ? std::nullopt : std::optional<Vec2>(it->second.home);
}

}  // namespace slam::planner

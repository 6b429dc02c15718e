// Fleet orchestration: goal fan-out, planning, exploration, due waypoints.
#include "planner/core/fleet.hpp"

namespace slam::planner {

Status validate(const FleetConfig& config) {
  if (auto s = validate(config.goals); !s) return s;
  if (auto s = validate(config.explore); !s) return s;
  if (auto s = validate(config.relocalise); !s) return s;
  return validate(config.planner);
}

Fleet::Fleet(const FleetConfig& config) : config_(config), planner_(config.planner) {}

void Fleet::start(Robot& robot, const Goal& goal) {
  robot.tracker.set_goal(goal, robot.position, robot.home);
  robot.idle_since_ns = -1;
  robot.next_search_ns = 0;
  if (goal.mode == GoalMode::Explore) exploration_complete_ = false;
}

UnknownPolicy Fleet::policy(const Robot& robot) const {
  return robot.tracker.mode() == GoalMode::Explore ? config_.explore.unknown : config_.planner.unknown;
}

void Fleet::observe(const std::string& robot_id, Vec2 position) {
  auto [it, inserted] = robots_.try_emplace(robot_id, Robot{GoalTracker(config_.goals), position, position,
                                                            ProgressWatch{}, LocalisationWatch{}, 0, -1, 0});
  Robot& robot = it->second;
  robot.position = position;
  robot.localisation.observe_position(position, config_.relocalise);
  if (!inserted) {
    robot.tracker.update_position(position);
    return;
  }
  if (const auto home = restored_homes_.find(robot_id); home != restored_homes_.end()) {
    robot.home = home->second;
    restored_homes_.erase(home);
  }
  const auto own = pending_.find(robot_id);
  const KeptGoal* kept = own == pending_.end() ? nullptr : &own->second;
  if (fleet_goal_ && (kept == nullptr || fleet_goal_->order > kept->order)) kept = &*fleet_goal_;
  if (kept != nullptr) start(robot, kept->goal);
  if (own != pending_.end()) pending_.erase(own);
}

void Fleet::restore_home(const std::string& robot_id, Vec2 home) {
  if (robots_.count(robot_id) == 0) restored_homes_[robot_id] = home;
}

void Fleet::observe_uncertainty(const std::string& robot_id, double sigma_m) {
  if (const auto it = robots_.find(robot_id); it != robots_.end()) {
    it->second.localisation.observe_uncertainty(sigma_m, config_.relocalise);
  }
}

void Fleet::take_revisits(std::vector<Revisit>& out) {
  out.insert(out.end(), revisits_.begin(), revisits_.end());
  revisits_.clear();
}

void Fleet::forget(const std::string& robot_id) {
  robots_.erase(robot_id);
  pending_.erase(robot_id);
  restored_homes_.erase(robot_id);
  claims_.erase(robot_id);
}

Result<size_t> Fleet::set_goal(const std::string& robot_id, const Goal& goal) {
  SLAM_TRY(validate(goal));
  const uint64_t order = ++goal_order_;
  // A new exploration order gives every frontier another chance.
  if (goal.mode == GoalMode::Explore) blacklist_.clear();
  if (robot_id == kAllRobots) {
    if (goal.mode == GoalMode::Explore || goal.mode == GoalMode::Stop) {
      fleet_goal_ = KeptGoal{goal, order};
    } else {
      fleet_goal_.reset();
    }
    for (auto& [id, robot] : robots_) start(robot, goal);
    return robots_.size();
  }
  auto it = robots_.find(robot_id);
  if (it != robots_.end()) {
    start(it->second, goal);
    return size_t{1};
  }
  if (pending_.size() >= kMaxPendingGoals && pending_.count(robot_id) == 0) {
    return Error{"unknown robot '" + robot_id + "' and " + std::to_string(kMaxPendingGoals) +
                 " goals already wait for robots not seen yet"};
  }
  pending_[robot_id] = KeptGoal{goal, order};
  return size_t{0};
}

const Goal* Fleet::pending_goal(const std::string& robot_id) const {
  auto it = pending_.find(robot_id);
  return it == pending_.end() ? nullptr : &it->second.goal;
}

void Fleet::grid_changed(const PlanningGrid& grid, std::optional<std::span<const CellBox>> changed) {
  if (changed) {
    for (const CellBox& box : *changed) frontiers_.update(grid, box);
  } else {
    frontiers_.rebuild(grid);
  }
  for (auto& [id, robot] : robots_) robot.tracker.check_path(grid, policy(robot));
}

void Fleet::tick(const PlanningGrid& grid, int64_t now_ns) {
  if (grid.empty()) return;
  explore(grid, now_ns);
  plan_paths(grid, now_ns);
  // A frontier that turned out unreachable was dropped by plan_paths: offer another at once.
  explore(grid, now_ns);
  plan_paths(grid, now_ns);
}

void Fleet::give_up(Vec2 target, int64_t now_ns) {
  blacklist_.add(target, now_ns, static_cast<int64_t>(config_.explore.blacklist_rest_s * 1e9),
                 config_.explore.blacklist_radius_m);
}

void Fleet::plan_paths(const PlanningGrid& grid, int64_t now_ns) {
  for (auto& [id, robot] : robots_) {
    GoalTracker& t = robot.tracker;
    if (!robot.owned || !t.needs_plan()) continue;
    const PlanResult result = planner_.plan_for_robot(grid, robot.position, t.plan_target(), policy(robot),
                                                      t.target_stood_on(), config_.planner.goal_algorithm);
    if (result.ok()) {
      t.set_path(result.path);
      continue;
    }
    // A blocked start says nothing about the frontier: only its own failures give it up.
    if (t.has_frontier() && result.status != PlanStatus::StartBlocked) give_up(t.plan_target(), now_ns);
    t.plan_failed(std::string(msg::plan_status_name(result.status)) + ": " + result.reason);
  }
}

double Fleet::way_to_go(const Robot& robot) const {
  const GoalTracker& t = robot.tracker;
  const auto rest = t.remaining();
  // Not planned yet (or re-planning): the straight line is all there is.
  if (rest.empty()) return distance(robot.position, t.plan_target());
  double d = distance(robot.position, rest.front());
  for (size_t i = 1; i < rest.size(); ++i) d += distance(rest[i - 1], rest[i]);
  return d;
}

void Fleet::release_frontiers(const PlanningGrid& grid, int64_t now_ns) {
  for (auto& [id, robot] : robots_) {
    if (!robot.owned) continue;
    GoalTracker& t = robot.tracker;
    if (const auto reached = t.take_reached_frontier()) {
      const auto cell = grid.cell_at(*reached);
      if (cell && frontiers_.is_frontier(*cell, grid)) give_up(*reached, now_ns);
    }
    if (!t.has_frontier()) continue;
    // Drop frontiers that vanished (explored by someone) or that the robot stopped approaching.
    const auto cell = grid.cell_at(t.plan_target());
    if (!cell || !frontiers_.is_frontier(*cell, grid)) {
      t.drop_frontier();
    } else if (robot.progress.stalled(way_to_go(robot), now_ns, config_.explore)) {
      give_up(t.plan_target(), now_ns);
      t.drop_frontier();
    }
  }
}

void Fleet::relocalise(int64_t now_ns) {
  for (auto& [id, robot] : robots_) {
    if (!robot.owned) continue;
    GoalTracker& t = robot.tracker;
    if (t.revisiting()) {
      // Tied again on the way back (or stuck): it explores on from where it is.
      if (robot.localisation.tied(config_.relocalise) ||
          robot.progress.stalled(way_to_go(robot), now_ns, config_.explore)) {
        t.drop_frontier();
      }
      continue;
    }
    if (!t.has_frontier()) continue;
    if (const auto place = robot.localisation.take_return(config_.relocalise)) {
      t.revisit(*place);
      robot.progress.start(*place, now_ns);
      revisits_.push_back(Revisit{id, *place, robot.localisation.sigma_m()});
    }
  }
}

void Fleet::explore(const PlanningGrid& grid, int64_t now_ns) {
  if (!frontiers_.matches(grid)) frontiers_.rebuild(grid);
  relocalise(now_ns);
  release_frontiers(grid, now_ns);
  std::vector<ExploringRobot> seekers;
  std::vector<std::string> ids;
  for (auto& [id, robot] : robots_) {
    if (!robot.owned || !robot.tracker.wants_frontier() || now_ns < robot.next_search_ns) continue;
    // Nothing observed around the robot yet (or it is walled in): no frontier is known to be
    // reachable from it, which says nothing about the frontiers. It waits for the map instead of
    // giving up. (Observed: a known passable cell nearby, whatever the exploration policy.)
    if (!planner_.robot_start(grid, robot.position, UnknownPolicy::Blocked)) {
      robot.idle_since_ns = -1;
      robot.next_search_ns = now_ns + static_cast<int64_t>(config_.explore.retry_period_s * 1e9);
      continue;
    }
    seekers.push_back(ExploringRobot{static_cast<uint32_t>(ids.size()), robot.position});
    ids.push_back(id);
  }
  if (seekers.empty()) return;

  frontiers_.cluster(grid, config_.explore.min_cluster_cells, clusters_);
  eligible_.assign(clusters_.size(), 1);
  bool resting = false;  // a frontier will be offered again: exploration is not over yet
  for (size_t c = 0; c < clusters_.size(); ++c) {
    const Vec2 target = grid.centre(clusters_[c].target);
    if (blacklist_.contains(target, config_.explore.blacklist_radius_m, now_ns)) {
      eligible_[c] = 0;
      resting = resting || blacklist_.rests(target, config_.explore.blacklist_radius_m, now_ns);
    }
    for (const auto& [id, robot] : robots_) {
      if (robot.tracker.has_frontier() &&
          distance(robot.tracker.plan_target(), target) <= config_.explore.blacklist_radius_m) {
        eligible_[c] = 0;
      }
    }
    if (claimed_elsewhere(target)) eligible_[c] = 0;
  }
  const auto cost = [&](Vec2 from, Vec2 to) -> std::optional<double> {
    const PlanResult r = planner_.plan_for_robot(grid, from, to, config_.explore.unknown);
    return r.ok() ? std::optional<double>(r.length_m) : std::nullopt;
  };
  const auto assignments =
      assign_frontiers(seekers, clusters_, eligible_, grid, config_.explore.gain_weight, cost);
  std::vector<bool> assigned(seekers.size(), false);
  for (const FrontierAssignment& a : assignments) {
    Robot& robot = robots_.at(ids[a.robot]);
    robot.tracker.set_frontier(a.target);
    robot.progress.start(a.target, now_ns);
    robot.idle_since_ns = -1;
    assigned[a.robot] = true;
  }
  std::vector<std::string> idle;
  for (size_t s = 0; s < seekers.size(); ++s) {
    if (!assigned[s]) idle.push_back(ids[s]);
  }
  settle_idle(idle, resting, now_ns);
}

void Fleet::settle_idle(const std::vector<std::string>& idle, bool frontiers_resting, int64_t now_ns) {
  if (idle.empty()) return;
  bool others_exploring = claimed_elsewhere(std::nullopt);
  for (const auto& [id, robot] : robots_) others_exploring = others_exploring || robot.tracker.has_frontier();
  const auto grace = static_cast<int64_t>(config_.explore.completion_grace_s * 1e9);
  bool completed = false;
  for (const std::string& id : idle) {
    Robot& robot = robots_.at(id);
    robot.next_search_ns = now_ns + static_cast<int64_t>(config_.explore.retry_period_s * 1e9);
    // While another robot explores, what it uncovers may be for this one, and a resting frontier
    // is offered again later: either way the grace restarts.
    if (robot.idle_since_ns < 0 || others_exploring || frontiers_resting) robot.idle_since_ns = now_ns;
    if (now_ns - robot.idle_since_ns < grace) continue;
    // Nothing this robot can reach is left: its exploration is over.
    robot.tracker.exploration_complete();
    completed = true;
  }
  if (!completed) return;
  bool still_exploring = false;
  for (const auto& [id, robot] : robots_) {
    if (!robot.owned) continue;
    still_exploring = still_exploring || robot.tracker.has_frontier() || robot.tracker.wants_frontier();
  }
  if (!still_exploring) exploration_complete_ = true;
}

bool Fleet::replan_around(const std::string& robot_id, const PlanningGrid& grid) {
  const auto it = robots_.find(robot_id);
  if (it == robots_.end() || !it->second.owned) return false;
  Robot& robot = it->second;
  GoalTracker& t = robot.tracker;
  const bool routed = t.mode() == GoalMode::Planned || t.mode() == GoalMode::Home || t.has_frontier() ||
                      t.homing() || t.revisiting();
  if (t.status() != GoalStatus::Active || !routed || grid.empty()) return false;
  const PlanResult result =
      planner_.plan_for_robot(grid, robot.position, t.plan_target(), policy(robot), t.target_stood_on());
  if (!result.ok()) return false;
  t.set_path(result.path);
  return true;
}

void Fleet::due_waypoints(int64_t now_ns, std::vector<DueWaypoint>& out) {
  out.clear();
  for (auto& [id, robot] : robots_) {
    GoalTracker& t = robot.tracker;
    if (!robot.owned || !t.should_send(now_ns)) continue;
    const auto wp = t.current_waypoint();
    if (!wp) continue;
    const auto rest = t.remaining();
    out.push_back(DueWaypoint{id, *wp, std::vector<Vec2>(rest.begin(), rest.end())});
  }
}

std::vector<std::string> Fleet::take_changed() {
  std::vector<std::string> out;
  for (auto& [id, robot] : robots_) {
    if (!robot.owned || robot.tracker.revision() == robot.published_revision) continue;
    robot.published_revision = robot.tracker.revision();
    out.push_back(id);
  }
  return out;
}

size_t Fleet::update_ownership(const std::function<bool(const std::string&)>& owns) {
  size_t owned = 0;
  for (auto& [id, robot] : robots_) {
    const bool now_owned = owns(id);
    owned += now_owned ? 1 : 0;
    if (now_owned == robot.owned) continue;
    robot.owned = now_owned;
    if (now_owned) {
      robot.tracker.take_over();
      robot.idle_since_ns = -1;
      robot.next_search_ns = 0;
    } else {
      robot.tracker.drop_frontier();
    }
  }
  return owned;
}

bool Fleet::owns(const std::string& robot_id) const {
  const auto it = robots_.find(robot_id);
  return it != robots_.end() && it->second.owned;
}

void Fleet::claim(const std::string& robot_id, std::optional<Vec2> target) {
  if (target) {
    claims_[robot_id] = *target;
  } else {
    claims_.erase(robot_id);
  }
}

bool Fleet::claimed_elsewhere(std::optional<Vec2> target) const {
  for (const auto& [id, claimed] : claims_) {
    if (owns(id)) continue;
    if (!target || distance(claimed, *target) <= config_.explore.blacklist_radius_m) return true;
  }
  return false;
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

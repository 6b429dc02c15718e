// PathPlanner: request validation, dispatch and status reasons.
#include "planner/core/path_planner.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>

#include "planner/core/path_reduction.hpp"

namespace slam::planner {

namespace {

bool finite(Vec2 p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

std::string describe(Vec2 p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f)", p.x, p.y);
  return buf;
}

// Why no path exists: under Allowed the search crossed unexplored space too, so known walls
// separate start and goal; under Blocked the unexplored space may still hold a way.
std::string no_path_reason(Vec2 start, Vec2 goal, UnknownPolicy policy) {
  const std::string route = "no path from " + describe(start) + " to " + describe(goal);
  return policy == UnknownPolicy::Allowed
             ? route + ": unreachable, enclosed by known walls (not even a way through unexplored space)"
             : route + " through explored space (unexplored space is blocked)";
}

// Why a cell cannot be a start or goal: an unknown one is impassable only under Blocked.
std::string impassable_reason(const PlanningGrid& grid, Cell cell) {
  return grid.unknown(cell) ? " is in unexplored space (unexplored space is blocked)"
                            : " is in an obstacle or too close to one";
}

constexpr std::string_view kAlgorithms = "astar, rrtconnect, rrtstar, prmstar or fmtstar";

std::string metres(double m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f m", m);
  return buf;
}

PlanResult failure(PlanStatus status, std::string reason) {
  PlanResult r;
  r.status = status;
  r.reason = std::move(reason);
  return r;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Status validate(const PlannerConfig& config) {
  if (!std::isfinite(config.unknown_cost_factor) || config.unknown_cost_factor < 1.0) {
    return Error{"planner.unknown_cost_factor must be a finite number >= 1"};
  }
  if (!std::isfinite(config.max_time_budget_s) || config.max_time_budget_s <= 0.0) {
    return Error{"planner.max_time_budget_s must be positive"};
  }
  if (!std::isfinite(config.ompl_range_m) || config.ompl_range_m < 0.0) {
    return Error{"planner.ompl_range_m must be a finite number >= 0 (0: OMPL's default)"};
  }
  if (!std::isfinite(config.escape_radius_m) || config.escape_radius_m < 0.0) {
    return Error{"planner.escape_radius_m must be a finite number >= 0"};
  }
  if (config.ompl_fmt_samples < 100) return Error{"planner.ompl_fmt_samples must be at least 100"};
  if (config.goal_algorithm != "astar" && !is_ompl_algorithm(config.goal_algorithm)) {
    return Error{"planner.goal_algorithm must be one of " + std::string(kAlgorithms)};
  }
  if (!std::isfinite(config.goal_time_budget_s) || config.goal_time_budget_s <= 0.0 ||
      config.goal_time_budget_s > config.max_time_budget_s) {
    return Error{"planner.goal_time_budget_s must be positive and at most max_time_budget_s"};
  }
  return Status::ok();
}

PathPlanner::PathPlanner(const PlannerConfig& config)
    : config_(config), ompl_(config.ompl_seed, config.ompl_range_m, config.ompl_fmt_samples) {}

std::optional<PlanResult> PathPlanner::reject(const PlanningGrid& grid, const PathQuery& query) const {
  if (!finite(query.start)) return failure(PlanStatus::InvalidRequest, "start is not finite");
  if (!finite(query.goal)) return failure(PlanStatus::InvalidRequest, "goal is not finite");
  if (query.algorithm != "astar" && !is_ompl_algorithm(query.algorithm)) {
    return failure(PlanStatus::InvalidRequest,
                   "unknown algorithm '" + query.algorithm + "' (expected " + std::string(kAlgorithms) + ")");
  }
  if (!std::isfinite(query.time_budget_s) || query.time_budget_s <= 0.0) {
    return failure(PlanStatus::InvalidRequest, "time budget must be a positive number of seconds");
  }
  if (query.time_budget_s > config_.max_time_budget_s) {
    return failure(PlanStatus::InvalidRequest, "time budget " + std::to_string(query.time_budget_s) +
                                                   " s exceeds the limit " +
                                                   std::to_string(config_.max_time_budget_s) + " s");
  }
  if (grid.empty()) return failure(PlanStatus::NoMap, "no map received yet");
  const auto start = grid.cell_at(query.start);
  if (!start) {
    return failure(PlanStatus::InvalidRequest, "start " + describe(query.start) + " is outside the map");
  }
  const auto goal = grid.cell_at(query.goal);
  if (!goal) {
    return failure(PlanStatus::InvalidRequest, "goal " + describe(query.goal) + " is outside the map");
  }
  if (grid.impassable(*start, config_.unknown)) {
    return failure(PlanStatus::StartBlocked,
                   "start " + describe(query.start) + impassable_reason(grid, *start));
  }
  if (grid.impassable(*goal, config_.unknown)) {
    return failure(PlanStatus::GoalBlocked, "goal " + describe(query.goal) + impassable_reason(grid, *goal));
  }
  return std::nullopt;
}

PlanResult PathPlanner::run_astar(const PlanningGrid& grid, Cell from, Cell to, Vec2 start, Vec2 goal,
                                  UnknownPolicy policy) {
  const AstarOptions options{policy, config_.unknown_cost_factor};
  const PlanStatus status = astar_.search(grid, from, to, options, cells_);
  if (status != PlanStatus::Ok) {
    return failure(status, status == PlanStatus::NoPath ? no_path_reason(start, goal, policy)
                                                        : std::string(msg::plan_status_name(status)));
  }
  PlanResult result;
  result.status = PlanStatus::Ok;
  result.path = reduce_cell_path(grid, cells_, start, goal, policy);
  result.length_m = path_length(result.path);
  return result;
}

PlanResult PathPlanner::run_ompl(const PlanningGrid& grid, Cell from, Cell to, Vec2 start, Vec2 goal,
                                 std::string_view algorithm, double budget_s, UnknownPolicy policy,
                                 bool astar_when_out_of_time) {
  try {
    OmplOutcome outcome = ompl_.plan(grid, start, goal, algorithm, budget_s, policy);
    if (outcome.status == PlanStatus::Ok) {
      PlanResult result;
      result.status = PlanStatus::Ok;
      result.path = shortcut(grid, drop_collinear(outcome.path), policy);
      result.length_m = path_length(result.path);
      return result;
    }
    if (outcome.status != PlanStatus::Timeout) return failure(outcome.status, std::move(outcome.reason));
    // OMPL cannot tell "no path" from "not found yet"; an exhaustive A* can.
    PlanResult astar = run_astar(grid, from, to, start, goal, policy);
    if (astar_when_out_of_time || astar.status == PlanStatus::NoPath) return astar;
    return failure(outcome.status, std::move(outcome.reason));
  } catch (const std::exception& e) {
    return failure(PlanStatus::InvalidRequest, std::string("OMPL failed: ") + e.what());
  }
}

double PathPlanner::escape_cells(const PlanningGrid& grid) const {
  return config_.escape_radius_m / grid.resolution();
}

std::optional<Cell> PathPlanner::robot_start(const PlanningGrid& grid, Vec2 position, UnknownPolicy policy) {
  const auto cell = grid.cell_at(position);
  if (!cell) return std::nullopt;
  return escape_.find(grid, *cell, escape_cells(grid), policy);
}

PlanResult PathPlanner::plan_for_robot(const PlanningGrid& grid, Vec2 start, Vec2 goal, UnknownPolicy policy,
                                       bool snap_goal, std::string_view algorithm) {
  const auto t0 = std::chrono::steady_clock::now();
  if (grid.empty()) return failure(PlanStatus::NoMap, "no map received yet");
  if (!finite(start)) return failure(PlanStatus::InvalidRequest, "start is not finite");
  if (!finite(goal)) return failure(PlanStatus::InvalidRequest, "goal is not finite");
  const auto start_cell = grid.cell_at(start);
  if (!start_cell)
    return failure(PlanStatus::InvalidRequest, "start " + describe(start) + " is outside the map");
  const auto goal_cell = grid.cell_at(goal);
  if (!goal_cell)
    return failure(PlanStatus::InvalidRequest, "goal " + describe(goal) + " is outside the map");
  const double radius = escape_cells(grid);
  const auto from = escape_.find(grid, *start_cell, radius, policy);
  if (!from) {
    return failure(PlanStatus::StartBlocked,
                   "start " + describe(start) + impassable_reason(grid, *start_cell) +
                       " with no passable cell within " + metres(config_.escape_radius_m));
  }
  std::optional<Cell> to = *goal_cell;
  if (snap_goal) {
    to = escape_.find(grid, *goal_cell, radius, policy);
  } else if (grid.impassable(*goal_cell, policy)) {
    to.reset();
  }
  if (!to) {
    return failure(PlanStatus::GoalBlocked, "goal " + describe(goal) + impassable_reason(grid, *goal_cell));
  }
  const bool escaped = !(*from == *start_cell);
  const Vec2 leg_start = escaped ? grid.centre(*from) : start;
  const Vec2 leg_goal = *to == *goal_cell ? goal : grid.centre(*to);
  // A goal never fails for want of sampling time: A* takes over then.
  PlanResult result = algorithm == "astar" ? run_astar(grid, *from, *to, leg_start, leg_goal, policy)
                                           : run_ompl(grid, *from, *to, leg_start, leg_goal, algorithm,
                                                      config_.goal_time_budget_s, policy, true);
  if (result.ok() && escaped) {
    result.path.insert(result.path.begin(), start);
    result.length_m = path_length(result.path);
  }
  result.planning_time_s = seconds_since(t0);
  return result;
}

PlanResult PathPlanner::plan(const PlanningGrid& grid, const PathQuery& query) {
  const auto t0 = std::chrono::steady_clock::now();
  if (auto rejected = reject(grid, query)) return std::move(*rejected);
  PlanResult result;
  if (query.algorithm == "astar") {
    result = run_astar(grid, *grid.cell_at(query.start), *grid.cell_at(query.goal), query.start, query.goal,
                       config_.unknown);
  } else {
    result = run_ompl(grid, *grid.cell_at(query.start), *grid.cell_at(query.goal), query.start, query.goal,
                      query.algorithm, query.time_budget_s, config_.unknown, false);
  }
  result.planning_time_s = seconds_since(t0);
  return result;
}

}  // namespace slam::planner

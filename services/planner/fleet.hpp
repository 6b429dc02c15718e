#pragma once
// Every known robot's goal in one place: applies goals (one robot or "*" for all known robots),
// plans and re-plans their paths, runs frontier exploration across them and says which waypoint
// commands are due. Pure logic; the service feeds it observations, grids and the time.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/result.hpp"
#include "planner/frontier_assignment.hpp"
#include "planner/frontiers.hpp"
#include "planner/goal_tracker.hpp"
#include "planner/path_planner.hpp"

namespace slam::planner {

inline constexpr const char* kAllRobots = "*";

struct FleetConfig {
  TrackerConfig goals;
  ExplorerConfig explore;
  PlannerConfig planner;
};

Status validate(const FleetConfig& config);

struct DueWaypoint {
  std::string robot_id;
  Vec2 waypoint;
  std::vector<Vec2> remaining;  // the current waypoint and the ones after it
};

class Fleet {
 public:
  explicit Fleet(const FleetConfig& config);

  // A robot's position; the first one makes it known and fixes its home.
  void observe(const std::string& robot_id, Vec2 position);
  // A goal for one known robot, or for every known robot with robot_id "*".
  Status set_goal(const std::string& robot_id, const Goal& goal);
  // After a snapshot (box empty) or a patch (its box): refresh frontiers, check paths.
  void grid_changed(const PlanningGrid& grid, std::optional<CellBox> box);
  // Plans what needs planning and assigns frontiers; call after observations and grid changes.
  void tick(const PlanningGrid& grid, int64_t now_ns);
  // Waypoint commands due at now_ns (see GoalTracker::should_send).
  void due_waypoints(int64_t now_ns, std::vector<DueWaypoint>& out);
  // Robots whose path or status changed since the last call: their RobotPath needs publishing.
  std::vector<std::string> take_changed();

  const GoalTracker* tracker(const std::string& robot_id) const;
  std::optional<Vec2> home(const std::string& robot_id) const;
  size_t size() const { return robots_.size(); }
  // True once an exploring robot found no frontier left; false again when exploration restarts.
  bool exploration_complete() const { return exploration_complete_; }
  const FrontierBlacklist& blacklist() const { return blacklist_; }

 private:
  struct Robot {
    GoalTracker tracker;
    Vec2 position;
    Vec2 home;
    ProgressWatch progress;
    uint64_t published_revision = 0;
  };

  void plan_paths(const PlanningGrid& grid);
  void explore(const PlanningGrid& grid, int64_t now_ns);

  FleetConfig config_;
  PathPlanner planner_;
  FrontierMap frontiers_;
  FrontierBlacklist blacklist_;
  std::vector<FrontierCluster> clusters_;
  std::vector<uint8_t> eligible_;  // per cluster, 0 = taken or blacklisted
  std::map<std::string, Robot> robots_;
  bool exploration_complete_ = false;
};

}  // namespace slam::planner

#pragma once
// FleetCoordinator: the traffic rules (traffic_rules.hpp) applied to the fleet. It feeds the rules
// from the Fleet and rewrites the due waypoint commands of the robots owned here. With several
// planners each one decides for every robot from what it sees (RobotState positions, RobotPath paths
// of the other planners' robots, the goals every planner reads) and applies only its own robots'
// orders. The design: docs/services.md, "The planner's fleet coordination".
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "planner/core/fleet.hpp"
#include "planner/core/planning_grid.hpp"
#include "planner/core/traffic_rules.hpp"

namespace slam::planner {

// The Fleet's side: which robot has which slot, the other planners' paths, and the due waypoint
// commands rewritten for the robots told to wait or yield.
class FleetCoordinator {
 public:
  explicit FleetCoordinator(const CoordinationConfig& config);

  bool enabled() const { return config_.enabled; }
  // Every robot's latest position (owned or not).
  void observe(const std::string& robot_id, Vec2 position);
  // A robot dropped from the fleet (forgotten): no longer an obstacle for the others. A robot that
  // only went silent stays one, where it was last seen.
  void forget(const std::string& robot_id);
  // A robot of another planner: the waypoints it still drives to (empty when it has none).
  void report_path(const std::string& robot_id, std::span<const Vec2> ahead);
  // Decides for every robot from the fleet's routes; call after Fleet::tick. A robot of this planner
  // kept waiting gets a route around the other robots (Fleet::replan_around) when one exists.
  void coordinate(Fleet& fleet, const PlanningGrid& grid, int64_t now_ns);
  // Rewrites `due` (Fleet::due_waypoints) for robots owned here: a waiting robot is sent where it
  // stays, a yielding one where it steps aside, and a robot whose order changed gets its command at
  // once (a released one its route's waypoint again).
  void dispatch(const Fleet& fleet, std::vector<DueWaypoint>& due);

  // Robots told to wait or yield now, the longest current wait (s) and the longest seen so far.
  size_t held() const;
  double longest_wait_s(int64_t now_ns) const;
  double longest_wait_seen_s() const { return longest_wait_seen_s_; }
  uint64_t deadlocks() const { return rules_.deadlocks(); }
  uint64_t replans() const { return replans_; }
  // The order for a robot (Go for one never seen).
  TrafficOrder order(const std::string& robot_id) const;

  // For logs and tools: what holds a robot, with the robots named.
  struct Held {
    TrafficOrder order = TrafficOrder::Go;
    Vec2 hold;
    std::string blocker;  // empty: none
    bool deadlock = false;
    bool section = false;
  };
  Held hold_of(const std::string& robot_id) const;
  // How long the robot has been held (0 when it is not).
  double wait_s(const std::string& robot_id, int64_t now_ns) const;
  // The robot whose way is cleared now (empty: none).
  std::string leader() const;

 private:
  struct Slot {
    std::string id;
    Vec2 position;
    bool seen = false;
    std::vector<Vec2> reported;  // another planner's robot: its RobotPath's remaining waypoints
    uint64_t goal_id = 0;
    Vec2 target;
    bool active = false;
    int64_t route_since_ns = 0;
    TrafficOrder sent_order = TrafficOrder::Go;
    Vec2 sent_hold;
    int64_t replanned_ns = std::numeric_limits<int64_t>::min() / 2;    // a way around last looked for
    int64_t leg_checked_ns = std::numeric_limits<int64_t>::min() / 2;  // its way back last checked
  };
  size_t slot(const std::string& robot_id);
  // A robot of this planner told to go from off its route's leg (where it stepped aside or was
  // pushed to) drives straight to its waypoint: when that way would run into a wall, its route is
  // planned again from where it stands (checked, and re-planned, at most once a second).
  void replan_off_leg(Fleet& fleet, const PlanningGrid& grid, int64_t now_ns);
  // Re-plans the robots of this planner held longer than replan_after_s (and again as often), on a
  // copy of the grid with every other robot drawn in; a robot keeps its route when there is no other.
  void replan_held(Fleet& fleet, const PlanningGrid& grid, int64_t now_ns);

  CoordinationConfig config_;
  TrafficRules rules_;
  std::map<std::string, size_t> slots_;
  std::vector<Slot> robots_;
  std::vector<TrafficRobot> inputs_;
  std::vector<TrafficDecision> decisions_;
  PlanningGrid obstacles_;  // the grid with stopped robots in it (a copy, reused)
  uint64_t replans_ = 0;
  double longest_wait_seen_s_ = 0.0;
};

}  // namespace slam::planner

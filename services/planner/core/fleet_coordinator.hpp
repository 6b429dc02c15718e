#pragma once
// Keeps robots from meeting: every tick each moving robot reserves the stretch of its path ahead
// (a polyline `lookahead_m` long, as wide as two robots plus a clearance), in priority order. A robot
// whose stretch would come too close to a higher-priority robot's reservation, or to another robot's
// body, waits where it is; one standing on the reservation it gives way to steps aside (yields) to
// the nearest free place off it. Waits form a wait-for graph: a cycle (two robots nose to nose in
// a corridor) is a deadlock and one of its robots yields (the next one when it has nowhere to go);
// a robot waited on that has no route (it stopped) yields too, and one held by a stopped robot
// that cannot move plans a way around it. Priority: the earlier route first (ties by a hash of the
// id), so a waiting robot only rises and none waits forever while the others keep arriving.
//
// One-way narrow stretches (`one_way_sections`): where the path runs through a passage in which no robot can
// stand clear of another's way (no free room `reach` to either side of the path: a door, a single-lane
// corridor), the whole stretch ahead, up to `section_horizon_m`, is reserved as one section once its entry is
// within `lookahead_m`. A robot does not enter a section that a robot inside it, or a robot of higher
// priority waiting to enter it, travels in the opposite direction: it waits `reach` before the mouth
// instead of meeting the other one inside where neither can step aside (the queues from both ends
// that filled a maze corridor). Section waits alone form no cycle: one points from a robot outside
// the stretch to one inside it or to one of higher priority, and robots inside never wait for a
// section. A waiting robot lets through only robots already inside and robots ranked above it, and
// its rank never falls while it waits (a new route ranks last), so a section wait lasts at most
// while the robots ranked above it cross once each, (robots - 1) x (stretch + lookahead) / speed,
// provided the robots inside move. That proviso is not guaranteed: a robot inside can be held by a
// body at the far mouth, and that cycle is broken by yielding, which needs room (below). So this is
// a bound on section waits, not on every wait (docs/performance.md has the measured waits).
//
// Breaking a cycle: a member steps off the way of the robot waiting for it (that removes the
// cycle's edge into it); when no member has room, the robots queued behind the members step off
// the way first, nearest first (a cascading back-off), so a member can back into the room made.
//
// Clearing the way of the longest-waiting robot (`clear_way`, way_clearing.cpp): the rules above are
// local (a step aside within yield_search_m), and on a tree-like map (a perfect maze: one way between
// two places, corridors one robot wide) a jam has no room near it; the passing places are the side
// branches. So the robot waiting longest, once clear_after_s, becomes the leader: its way
// ahead (clear_horizon_m) is reserved for it alone, robots whose reservation enters that way wait
// off it, and every robot standing on it is pushed into the nearest side room off it (within
// clear_search_m, passing no other robot), the robot furthest ahead the deepest so the ones behind it
// fit in the same branch; off the whole of the leader's route, not only the part cleared, since on a
// tree a robot left further along it would be met again. One with no side room in reach is pushed on
// ahead along the route, never on a straight way that brings its body nearer a wall (a robot stops
// against what it touches). The leader goes whenever no body stands
// close ahead and every robot on its way has somewhere to go. It stays the leader until its route
// ends or changes (the window cleared slides with it), or until neither it nor a robot clearing its
// way has moved for clear_stall_s (then the others are tried first). The longest wait leads, so a
// robot's wait is bounded by the routes of the leaders that waited longer than it, unless a jam has
// no side room within clear_search_m (a stall).
//
// Plain C++: TrafficRules decides from plain inputs; FleetCoordinator feeds it from the Fleet and
// rewrites the due waypoint commands of the robots owned here. With several planners each one
// decides for every robot from what it sees (RobotState positions, RobotPath paths of the other
// planners' robots, the goals every planner reads) and applies only its own robots' orders.
//
// Steady state allocates nothing: buffers are kept per robot slot and reused; a tick costs
// O(moving robots^2) distance checks (pairs further apart than two reservations are skipped at
// once) plus a bounded search per yielding robot, whatever the history.
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/fleet.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

struct CoordinationConfig {
  bool enabled = true;
  double robot_radius_m = 0.2;    // a robot's body plus its pose error
  double clearance_m = 0.15;      // kept free between two bodies
  double lookahead_m = 2.0;       // path reserved ahead of a moving robot
  double body_lookahead_m = 0.8;  // how far ahead another robot's body stops this one
  double yield_search_m = 3.0;    // how far a robot looks for a place to step aside
  double yield_step_m = 1.0;      // a yielding robot is sent at most this far at a time
  // A robot kept waiting this long (a stopped robot, a jam no one can step out of) plans a way
  // around the robots in its way, and again as often while it waits.
  double replan_after_s = 4.0;
  // One-way narrow stretches (below). Off by default: measured in the maze they did not shorten
  // the longest wait and in an offline model they halved the targets reached (docs/performance.md).
  bool one_way_sections = false;
  // How much of a narrow stretch ahead is reserved one way at most (a long corridor in parts).
  double section_horizon_m = 12.0;
  // Clearing the way of the highest-priority robot kept waiting (the leader; above).
  bool clear_way = true;
  double clear_after_s = 5.0;    // a robot waiting this long may lead
  double clear_horizon_m = 5.0;  // the leader's way reserved and cleared
  double clear_search_m = 8.0;   // how far a robot on it looks for side room
  double clear_stall_s = 10.0;   // a leader not moving this long gives the lead up
};

Status validate(const CoordinationConfig& config);

enum class TrafficOrder : uint8_t { Go, Wait, Yield };

// One robot as the rules see it.
struct TrafficRobot {
  Vec2 position;
  std::span<const Vec2> ahead;  // waypoints still to drive to; empty: no route (stopped)
  int64_t route_since_ns = 0;   // when its route started: earlier is higher priority
  uint32_t tie = 0;             // breaks equal route_since_ns (same on every planner)
};

struct TrafficDecision {
  TrafficOrder order = TrafficOrder::Go;
  Vec2 hold;             // Wait: where to stay; Yield: where to drive to now
  int32_t blocker = -1;  // the robot it waits for or gives way to
  int64_t waiting_since_ns = -1;
  bool deadlock = false;  // yields to break a wait-for cycle
  bool section = false;   // waits before a narrow stretch another robot uses the other way
};

class TrafficRules {
 public:
  explicit TrafficRules(const CoordinationConfig& config) : config_(config) {}

  // Decides for every robot; `decisions` keeps one entry per robot between calls (same indices),
  // which carries when each robot started waiting.
  void decide(const PlanningGrid& grid, std::span<const TrafficRobot> robots, int64_t now_ns,
              std::vector<TrafficDecision>& decisions);

  // Deadlocks broken since the start.
  uint64_t deadlocks() const { return deadlocks_; }
  // Leaders whose way was cleared since the start.
  uint64_t clearings() const { return clearings_; }
  // The robot whose way is cleared now (-1: none).
  int32_t leader() const { return leader_; }

 private:
  double reach() const { return 2.0 * config_.robot_radius_m + config_.clearance_m; }
  // The robot's way from where it is, cut at `length` metres, appended to `out`.
  static void append_way(const TrafficRobot& robot, double length, std::vector<Vec2>& out);
  // The point `length` metres along the robot's way (its destination when the way is shorter).
  static Vec2 point_along(const TrafficRobot& robot, double length);
  // True when a robot at p driving along `along` (a unit vector) has no free room `reach` plus a
  // margin to either side: another robot cannot stand clear of its way there.
  bool narrow_at(const PlanningGrid& grid, Vec2 p, Vec2 along) const;
  // Section i: the narrow stretch of the robot's way that begins within lookahead_m (none: empty),
  // with entry_m_[i] how far along the way it begins.
  void build_section(const PlanningGrid& grid, size_t i, const TrafficRobot& robot);
  std::span<const Vec2> section(size_t i) const;
  // True when the polylines come closer than `gap` somewhere they run in opposite directions.
  static bool opposed(std::span<const Vec2> a, std::span<const Vec2> b, double gap);
  // Decides section_blocker_: robots inside a section first, then by priority.
  void grant_sections(std::span<const TrafficRobot> robots);
  // The same as claim i (offsets in claim_at_).
  void build_claim(size_t i, const TrafficRobot& robot, double length);
  std::span<const Vec2> claim(size_t i) const;
  // True when the two polylines come closer than `distance` anywhere.
  static bool near(std::span<const Vec2> a, std::span<const Vec2> b, double distance);
  // Where robot i should drive to leave `away` (a polyline) and every other body clear, preferring a
  // place `depth` further off it; false when no such place is within `search_m`.
  bool find_yield(const PlanningGrid& grid, std::span<const TrafficRobot> robots, size_t i,
                  std::span<const Vec2> away, Vec2& step, double search_m, double depth = 0.0);
  void resolve_deadlocks(const PlanningGrid& grid, std::span<const TrafficRobot> robots,
                         std::vector<TrafficDecision>& decisions);
  void yield(const PlanningGrid& grid, std::span<const TrafficRobot> robots, size_t i, size_t to,
             std::vector<TrafficDecision>& decisions);
  // The cascading back-off of the queues behind the cycle in cycle_ when none of it can yield.
  void back_off(const PlanningGrid& grid, std::span<const TrafficRobot> robots,
                std::vector<TrafficDecision>& decisions);
  // The leader rule (way_clearing.cpp): keeps, releases or chooses the leader, then clears its way.
  void clear_way(const PlanningGrid& grid, std::span<const TrafficRobot> robots, int64_t now_ns,
                 std::vector<TrafficDecision>& decisions);
  bool keep_leader(std::span<const TrafficRobot> robots, int64_t now_ns);
  // True when robot i driving straight to `to` comes no closer to another body than `reach` (or than
  // it is already), nor within `reach` of a place another robot was sent to this tick: at a
  // simulated 4x speed a position is some 0.1-0.2 m old by the time a command acts on it.
  bool keeps_apart(std::span<const TrafficRobot> robots, size_t i, Vec2 to) const;
  void choose_leader(std::span<const TrafficRobot> robots, int64_t now_ns,
                     const std::vector<TrafficDecision>& decisions);

  CoordinationConfig config_;
  std::vector<uint32_t> order_;  // robots by priority, highest first
  std::vector<Vec2> claim_points_;
  std::vector<uint32_t> claim_at_;       // claim i is claim_points_[claim_at_[2i], claim_at_[2i+1])
  std::vector<Vec2> long_points_;        // a longer claim for yield searches
  std::vector<uint8_t> granted_;         // claim reserved this tick
  std::vector<uint8_t> was_deadlocked_;  // yielded to break a cycle on the last tick
  std::vector<uint32_t> visit_;          // wait-for graph walk stamps
  std::vector<uint32_t> cycle_;          // the robots of one wait-for cycle
  std::vector<uint32_t> waited_by_;      // cycle member -> the member waiting for it
  std::vector<std::pair<uint32_t, uint32_t>> back_off_;  // (robot, the robot whose way to clear)
  std::vector<uint32_t> seen_stamp_;                     // yield search: grid cells seen, by query stamp
  std::vector<uint32_t> parent_;                         // yield search: the cell each was reached from
  std::vector<uint32_t> queue_;
  std::vector<Vec2> nearby_;     // yield search: the bodies near it
  std::vector<Vec2> committed_;  // where robots pushed off the leader's way were sent this tick
  std::vector<Vec2> section_points_;
  std::vector<uint32_t> section_at_;      // section i is section_points_[section_at_[2i], section_at_[2i+1])
  std::vector<double> entry_m_;           // way to section i's entry
  std::vector<int32_t> section_blocker_;  // the robot whose section robot i may not enter against
  std::vector<uint8_t> section_held_;     // robot i had its section granted on the last tick
  std::vector<uint32_t> section_order_;   // robots with a section, in the order they are granted
  std::vector<TrafficDecision> prior_;    // each robot's decision on the last tick
  int32_t leader_ = -1;                   // the robot whose way is cleared (-1: none)
  int64_t leader_route_ns_ = 0;           // its route_since_ns when it was chosen
  Vec2 leader_progress_at_;               // where it was when it last made progress
  int64_t leader_progress_ns_ = 0;
  std::vector<uint8_t> stalled_;                         // robot i led and its way could not be cleared
  std::vector<Vec2> way_points_;                         // the leader's way ahead
  std::vector<uint8_t> pushed_;                          // robot i clears the leader's way (while it leads)
  std::vector<Vec2> pushed_from_;                        // where robot i was when it last moved for it
  std::vector<double> push_depth_;                       // how much further off the way robot i goes
  std::vector<std::pair<double, uint32_t>> push_order_;  // (distance along the way, robot)
  uint32_t stamp_ = 0;
  uint64_t deadlocks_ = 0;
  uint64_t clearings_ = 0;
};

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

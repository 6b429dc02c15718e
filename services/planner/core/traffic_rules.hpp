#pragma once
// The traffic rules: which robot goes, waits or steps aside, decided each tick from plain inputs
// (positions, the ways ahead, route ages). The design and its reasoning: docs/services.md, "The
// planner's fleet coordination". decide() runs the rules as passes, in this order; each unit states
// the invariant its pass keeps:
//   1. ranking          (traffic_rules.cpp)      the earlier route first; a waiting robot only rises
//   2. one-way sections (one_way_sections.cpp)   no robot enters a narrow stretch against its users
//   3. reservations     (reservations.cpp)       no robot drives into a higher-ranked reservation
//   4. deadlocks        (deadlock_breaking.cpp)  no wait-for cycle survives a tick with room to move
//   5. the leader       (way_clearing.cpp)       the longest wait gets its way cleared
// Passes 3 to 5 send robots aside through one search (step_aside.cpp). Passes 2 and 5 are not
// combined (leader_rule_on): a leader driving into a section against its users would undo it.
// Steady state allocates nothing: buffers are kept per robot slot and reused; a tick costs
// O(moving robots^2) distance checks plus a bounded search per robot sent aside.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/plan_types.hpp"
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
  // One-way narrow stretches (pass 2). Off by default: measured in the maze they did not shorten
  // the longest wait and in an offline model they halved the targets reached (docs/performance.md).
  bool one_way_sections = false;
  // How much of a narrow stretch ahead is reserved one way at most (a long corridor in parts).
  double section_horizon_m = 12.0;
  // Clearing the way of the robot kept waiting longest (the leader, pass 5).
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
  using Robots = std::span<const TrafficRobot>;
  using Decisions = std::vector<TrafficDecision>;

  // Shared by the passes (traffic_rules.cpp).
  double reach() const { return 2.0 * config_.robot_radius_m + config_.clearance_m; }
  // The robot's way from where it is, cut at `length` metres, appended to `out`.
  static void append_way(const TrafficRobot& robot, double length, std::vector<Vec2>& out);
  // The point `length` metres along the robot's way (its destination when the way is shorter).
  static Vec2 point_along(const TrafficRobot& robot, double length);
  // True when the two polylines come closer than `distance` anywhere.
  static bool near(std::span<const Vec2> a, std::span<const Vec2> b, double distance);
  // True when the polylines come closer than `gap` somewhere they run in opposite directions.
  static bool opposed(std::span<const Vec2> a, std::span<const Vec2> b, double gap);
  // Pass 1: order_, the moving robots by priority.
  void rank(Robots robots);
  // The leader rule runs unless it is off or one-way sections are on (the two are not combined).
  bool leader_rule_on() const { return config_.clear_way && !config_.one_way_sections; }
  // After the passes: when each robot started waiting.
  static void note_waits(Robots robots, int64_t now_ns, Decisions& decisions);

  // Pass 2, one-way sections (one_way_sections.cpp).
  void plan_sections(const PlanningGrid& grid, Robots robots);
  // True when a robot at p driving along `along` (a unit vector) has no free room `reach` plus a
  // margin to either side: another robot cannot stand clear of its way there.
  bool narrow_at(const PlanningGrid& grid, Vec2 p, Vec2 along) const;
  // Section i: the narrow stretch of the robot's way that begins within lookahead_m (none: empty),
  // with entry_m_[i] how far along the way it begins.
  void build_section(const PlanningGrid& grid, size_t i, const TrafficRobot& robot);
  std::span<const Vec2> section(size_t i) const;
  // Decides section_blocker_: robots inside a section first, then by priority.
  void grant_sections(Robots robots);
  // Where a robot kept out of its section waits: `reach` before the mouth (metres along its way).
  double section_wait_m(size_t i) const;

  // Pass 3, reservations and bodies (reservations.cpp).
  void reserve(const PlanningGrid& grid, Robots robots, Decisions& decisions);
  // Claim i: the way robot i reserves (offsets in claim_at_).
  void build_claim(size_t i, const TrafficRobot& robot, double length);
  std::span<const Vec2> claim(size_t i) const;
  // True when robot k's body stands close ahead on robot i's claim and robot i does not move away
  // from it (they part).
  bool body_ahead(Robots robots, size_t i, size_t k) const;

  // Pass 4, wait-for cycles (deadlock_breaking.cpp).
  void resolve_deadlocks(const PlanningGrid& grid, Robots robots, Decisions& decisions);
  // The cascading back-off of the queues behind the cycle in cycle_ when none of it can yield.
  void back_off(const PlanningGrid& grid, Robots robots, Decisions& decisions);

  // Pass 5, the leader rule (way_clearing.cpp): keeps, releases or chooses the leader, then clears
  // its way.
  void clear_way(const PlanningGrid& grid, Robots robots, int64_t now_ns, Decisions& decisions);
  bool keep_leader(Robots robots, int64_t now_ns);
  void choose_leader(Robots robots, int64_t now_ns, const Decisions& decisions);
  // Lists the robots on the leader's way in push_order_ and holds the ones about to enter it.
  void find_robots_on_way(Robots robots, std::span<const Vec2> way, Decisions& decisions);
  // Sends the robots in push_order_ off the leader's route; true when one on its way has nowhere
  // to go (stuck).
  bool push_off_way(const PlanningGrid& grid, Robots robots, std::span<const Vec2> route, int64_t now_ns,
                    Decisions& decisions);
  // The leader goes unless a body stands close ahead or the robots on its way are stuck.
  void lead(Robots robots, bool stuck, Decisions& decisions);
  // True when robot i driving straight to `to` comes no closer to another body than `reach` (or than
  // it is already), nor within `reach` of a place another robot was sent to this tick: at a
  // simulated 4x speed a position is some 0.1-0.2 m old by the time a command acts on it.
  bool keeps_apart(Robots robots, size_t i, Vec2 to) const;

  // Stepping aside, used by passes 3 to 5 (step_aside.cpp).
  void yield(const PlanningGrid& grid, Robots robots, size_t i, size_t to, Decisions& decisions);
  // Where robot i should drive to leave `away` (a polyline) and every other body clear, preferring a
  // place `depth` further off it; false when no such place is within `search_m`.
  bool find_yield(const PlanningGrid& grid, Robots robots, size_t i, std::span<const Vec2> away, Vec2& step,
                  double search_m, double depth = 0.0);

  CoordinationConfig config_;
  // Pass 1.
  std::vector<uint32_t> order_;  // robots by priority, highest first
  // Pass 2.
  std::vector<Vec2> section_points_;
  std::vector<uint32_t> section_at_;      // section i is section_points_[section_at_[2i], section_at_[2i+1])
  std::vector<double> entry_m_;           // way to section i's entry
  std::vector<int32_t> section_blocker_;  // the robot whose section robot i may not enter against
  std::vector<uint8_t> section_held_;     // robot i had its section granted on the last tick
  std::vector<uint32_t> section_order_;   // robots with a section, in the order they are granted
  // Pass 3.
  std::vector<Vec2> claim_points_;
  std::vector<uint32_t> claim_at_;      // claim i is claim_points_[claim_at_[2i], claim_at_[2i+1])
  std::vector<uint8_t> granted_;        // claim reserved this tick
  std::vector<TrafficDecision> prior_;  // each robot's decision on the last tick
  // Pass 4.
  std::vector<uint8_t> was_deadlocked_;                  // yielded to break a cycle on the last tick
  std::vector<uint32_t> visit_;                          // wait-for graph walk stamps
  std::vector<uint32_t> cycle_;                          // the robots of one wait-for cycle
  std::vector<uint32_t> waited_by_;                      // cycle member -> the member waiting for it
  std::vector<std::pair<uint32_t, uint32_t>> back_off_;  // (robot, the robot whose way to clear)
  uint64_t deadlocks_ = 0;
  // Pass 5.
  int32_t leader_ = -1;          // the robot whose way is cleared (-1: none)
  int64_t leader_route_ns_ = 0;  // its route_since_ns when it was chosen
  Vec2 leader_progress_at_;      // where it was when it last made progress
  int64_t leader_progress_ns_ = 0;
  std::vector<uint8_t> stalled_;                         // robot i led and its way could not be cleared
  std::vector<Vec2> way_points_;                         // the leader's way ahead
  std::vector<uint8_t> pushed_;                          // robot i clears the leader's way (while it leads)
  std::vector<Vec2> pushed_from_;                        // where robot i was when it last moved for it
  std::vector<double> push_depth_;                       // how much further off the way robot i goes
  std::vector<std::pair<double, uint32_t>> push_order_;  // (distance along the way, robot)
  std::vector<Vec2> committed_;  // where robots pushed off the leader's way were sent this tick
  uint64_t clearings_ = 0;
  // Stepping aside.
  std::vector<Vec2> long_points_;     // a longer claim for yield searches
  std::vector<uint32_t> seen_stamp_;  // grid cells seen, by query stamp
  std::vector<uint32_t> parent_;      // the cell each was reached from
  std::vector<uint32_t> queue_;
  std::vector<Vec2> nearby_;  // the bodies near the robot
  uint32_t stamp_ = 0;
};

}  // namespace slam::planner

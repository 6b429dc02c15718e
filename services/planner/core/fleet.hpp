#pragma once
// Every known robot's goal in one place: applies goals (one robot or "*" for all known robots),
// plans and re-plans their paths, runs frontier exploration across them and says which waypoint
// commands are due. Pure logic; the service feeds it observations, grids and the time.
//
// Several planners share the robots: each follows every robot's goal and position, but plans,
// explores and sends waypoints only for the robots it owns (update_ownership), so a robot that
// comes to it from a dead planner continues at once. The frontiers other planners' robots drive to
// (claim) are never offered to its own robots.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/frontier_assignment.hpp"
#include "planner/core/frontiers.hpp"
#include "planner/core/goal_tracker.hpp"
#include "planner/core/localisation_watch.hpp"
#include "planner/core/path_planner.hpp"

namespace slam::planner {

inline constexpr const char* kAllRobots = "*";

struct FleetConfig {
  TrackerConfig goals;
  ExplorerConfig explore;
  RelocaliseConfig relocalise;
  PlannerConfig planner;
};

Status validate(const FleetConfig& config);

// An exploring robot sent back to ground it is localised on (LocalisationWatch).
struct Revisit {
  std::string robot_id;
  Vec2 place;
  double sigma_m = 0.0;  // its uncertainty when it turned back
};

struct DueWaypoint {
  std::string robot_id;
  Vec2 waypoint;
  std::vector<Vec2> remaining;  // the current waypoint and the ones after it
};

class Fleet {
 public:
  // Goals kept for robots not seen yet; more are refused (a typo loop must not grow memory).
  static constexpr size_t kMaxPendingGoals = 1024;

  explicit Fleet(const FleetConfig& config);

  // A robot's position. The first one makes it known, fixes its home and starts the goal kept for
  // it: its own, or the standing fleet goal, whichever arrived later.
  void observe(const std::string& robot_id, Vec2 position);
  // A home kept from an earlier run (GoalStore): the robot's home once it is seen, instead of its
  // first position.
  void restore_home(const std::string& robot_id, Vec2 home);
  // The robot's position uncertainty (m) from the pose correction: exploring robots that pass
  // config.relocalise.return_sigma_m go back to where they were last tied to the map. Unknown
  // robots are ignored.
  void observe_uncertainty(const std::string& robot_id, double sigma_m);
  // The operator forgot the robot: its tracker, home, kept goal and claim go (a robot that reports
  // again starts afresh, at its new first position).
  void forget(const std::string& robot_id);
  // A goal for one robot, or for every robot with robot_id "*"; returns how many robots it
  // started for now. A goal for a robot not seen yet is kept until its first position (a
  // restarted planner reads goals before robot states). A "*" Explore or Stop goal stands: robots
  // appearing later adopt it (exploring and holding are fleet-wide; a target or a square was
  // chosen for the robots there at the time).
  Result<size_t> set_goal(const std::string& robot_id, const Goal& goal);
  // The goal kept for a robot not seen yet, if any.
  const Goal* pending_goal(const std::string& robot_id) const;
  // After a snapshot (no boxes) or a patch (its changed tiles): refresh frontiers, check paths.
  void grid_changed(const PlanningGrid& grid, std::optional<std::span<const CellBox>> changed);
  // Plans what needs planning and assigns frontiers; call after observations and grid changes.
  void tick(const PlanningGrid& grid, int64_t now_ns);
  // Plans robot_id's route again on `grid` (the map with stopped robots drawn in as obstacles, see
  // FleetCoordinator) and takes the new path only when one is found. False when it is not.
  bool replan_around(const std::string& robot_id, const PlanningGrid& grid);
  // Waypoint commands due at now_ns (see GoalTracker::should_send).
  void due_waypoints(int64_t now_ns, std::vector<DueWaypoint>& out);
  // Robots owned here whose path or status changed since the last call (or that were just taken
  // over): their RobotPath needs publishing.
  std::vector<std::string> take_changed();
  // Robots sent back to re-localise since the last call.
  void take_revisits(std::vector<Revisit>& out);

  // Asks `owns` about every known robot (each is owned until then). A robot taken over continues
  // its goal from where it is (GoalTracker::take_over); one given up drops its frontier, which
  // its new owner chooses. Returns how many robots are owned here.
  size_t update_ownership(const std::function<bool(const std::string&)>& owns);
  bool owns(const std::string& robot_id) const;
  // The frontier robot_id drives to under another planner (nullopt: none). Claims of robots owned
  // here are ignored: their own frontiers count.
  void claim(const std::string& robot_id, std::optional<Vec2> target);

  const GoalTracker* tracker(const std::string& robot_id) const;
  std::optional<Vec2> home(const std::string& robot_id) const;
  size_t size() const { return robots_.size(); }
  // True once the last exploring robot found no frontier left; false again when exploration
  // restarts.
  bool exploration_complete() const { return exploration_complete_; }
  const FrontierBlacklist& blacklist() const { return blacklist_; }

 private:
  struct Robot {
    GoalTracker tracker;
    Vec2 position;
    Vec2 home;
    ProgressWatch progress;  // toward its frontier, or the place it revisits
    LocalisationWatch localisation;
    uint64_t published_revision = 0;
    int64_t idle_since_ns = -1;  // exploring without a frontier to go to since then; -1: not
    int64_t next_search_ns = 0;  // no frontier search for this robot before then
    bool owned = true;           // planned, explored and streamed by this planner
  };
  struct KeptGoal {
    Goal goal;
    uint64_t order = 0;  // arrival order: the later of a robot's own and the fleet goal wins
  };

  void start(Robot& robot, const Goal& goal);
  // Exploring robots plan under the exploration policy, every other goal under the planner's.
  UnknownPolicy policy(const Robot& robot) const;
  void plan_paths(const PlanningGrid& grid, int64_t now_ns);
  // Sends exploring robots that lost their localisation back (LocalisationWatch) and ends the
  // revisits of those tied again. Owned robots only.
  void relocalise(int64_t now_ns);
  // Gives up a frontier target (see FrontierBlacklist).
  void give_up(Vec2 target, int64_t now_ns);
  void explore(const PlanningGrid& grid, int64_t now_ns);
  void release_frontiers(const PlanningGrid& grid, int64_t now_ns);
  // The robot's remaining path length to its frontier (what progress is measured on).
  double way_to_go(const Robot& robot) const;
  // Robots that found nothing: they wait while others explore or a given-up frontier only rests,
  // then head home after the grace.
  void settle_idle(const std::vector<std::string>& idle, bool frontiers_resting, int64_t now_ns);
  // True when a robot of another planner drives to a frontier within the blacklist radius of
  // `target` (any at all when `target` is empty).
  bool claimed_elsewhere(std::optional<Vec2> target) const;

  FleetConfig config_;
  PathPlanner planner_;
  FrontierMap frontiers_;
  FrontierBlacklist blacklist_;
  std::vector<FrontierCluster> clusters_;
  std::vector<uint8_t> eligible_;  // per cluster, 0 = taken or blacklisted
  std::map<std::string, Robot> robots_;
  std::map<std::string, KeptGoal> pending_;
  std::map<std::string, Vec2> restored_homes_;
  std::map<std::string, Vec2> claims_;  // frontiers of robots driven by other planners
  std::vector<Revisit> revisits_;
  std::optional<KeptGoal> fleet_goal_;
  uint64_t goal_order_ = 0;
  bool exploration_complete_ = false;
};

}  // namespace slam::planner

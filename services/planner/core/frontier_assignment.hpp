#pragma once
// Which exploring robot goes to which frontier cluster, which frontiers are given up on, and how
// to tell that a robot stopped getting closer to its frontier.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "common/core/result.hpp"
#include "planner/core/frontiers.hpp"
#include "planner/core/plan_types.hpp"

namespace slam::planner {

struct ExplorerConfig {
  uint32_t min_cluster_cells = 4;    // smaller clusters are noise, not worth a trip
  double gain_weight = 1.0;          // metres of travel one metre of frontier is worth
  double progress_timeout_s = 10.0;  // no progress this long: the frontier is given up
  double progress_min_m = 0.2;       // getting this much closer counts as progress
  double blacklist_radius_m = 0.5;   // clusters whose target lies this close to a blacklisted one are skipped
  double blacklist_rest_s = 30.0;    // a frontier given up once is offered again after this long
  // A robot finding no frontier waits this long before heading home: scans still in flight (its
  // own from the frontier it just reached, or another robot's) may reveal more.
  double completion_grace_s = 3.0;
  double retry_period_s = 0.5;  // a robot without a reachable frontier looks again this often
  // Exploring robots plan through unexplored cells (at the planner's unknown cost factor): sparse
  // range sensors leave unknown gaps between their beams, so known-free cells alone rarely connect;
  // a wall found on the way makes the path re-plan.
  UnknownPolicy unknown = UnknownPolicy::Allowed;
};

Status validate(const ExplorerConfig& config);

struct ExploringRobot {
  uint32_t robot = 0;  // caller's index, echoed in the assignment
  Vec2 position;
};

struct FrontierAssignment {
  uint32_t robot = 0;
  size_t cluster = 0;  // index into the clusters given
  Vec2 target;         // centre of the cluster's target cell
  double path_cost_m = 0.0;
};

// Travel cost between two map points, nothing when unreachable. Must never be less than the
// straight-line distance (the search prunes with it).
using PathCost = std::function<std::optional<double>(Vec2 from, Vec2 to)>;

// Greedy best-first matching on utility = gain_weight * cluster length (m) - path cost (m): the
// best (robot, cluster) pair first, then the best among the rest, so no two robots share a
// cluster. Path costs are computed lazily, bounded by straight-line distance, so only promising
// pairs pay for a search. `eligible[i]` 0 excludes cluster i (taken, blacklisted).
std::vector<FrontierAssignment> assign_frontiers(std::span<const ExploringRobot> robots,
                                                 std::span<const FrontierCluster> clusters,
                                                 std::span<const uint8_t> eligible, const PlanningGrid& grid,
                                                 double gain_weight, const PathCost& cost);

// Frontier targets given up on. The first failure near a place only rests it for a while (a robot
// standing in a corridor shows in the map as a wall until it moves on; another robot's scans may
// open the way); a second failure near the same place gives it up for good.
class FrontierBlacklist {
 public:
  // Gives up `target` at now_ns: until now_ns + rest_ns, or for good when an earlier entry lies
  // within radius_m of it.
  void add(Vec2 target, int64_t now_ns, int64_t rest_ns, double radius_m);
  // True when an entry within radius_m of p is in force at now_ns.
  bool contains(Vec2 p, double radius_m, int64_t now_ns) const;
  // True when an entry within radius_m of p only rests at now_ns (it is offered again later).
  bool rests(Vec2 p, double radius_m, int64_t now_ns) const;
  size_t size() const { return entries_.size(); }
  void clear() { entries_.clear(); }

 private:
  struct Entry {
    Vec2 point;
    int64_t until_ns;  // kForGood: for good
  };
  static constexpr int64_t kForGood = std::numeric_limits<int64_t>::max();
  std::vector<Entry> entries_;
};

// Progress of one robot toward one target, measured as the way still to go (the remaining path,
// not the straight line: a maze path may lead away from its target for a while): stalled() once
// that has not shrunk by progress_min_m within progress_timeout_s.
class ProgressWatch {
 public:
  void start(Vec2 target, int64_t now_ns);
  bool stalled(double remaining_m, int64_t now_ns, const ExplorerConfig& config);
  Vec2 target() const { return target_; }

 private:
  Vec2 target_;
  double best_remaining_ = 0.0;
  int64_t last_progress_ns_ = 0;
};

}  // namespace slam::planner

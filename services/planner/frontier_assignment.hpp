#pragma once
// Which exploring robot goes to which frontier cluster, which frontiers are given up on, and how
// to tell that a robot stopped getting closer to its frontier.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "common/result.hpp"
#include "planner/frontiers.hpp"
#include "planner/plan_types.hpp"

namespace slam::planner {

struct ExplorerConfig {
  uint32_t min_cluster_cells = 4;    // smaller clusters are noise, not worth a trip
  double gain_weight = 1.0;          // metres of travel one metre of frontier is worth
  double progress_timeout_s = 20.0;  // no progress this long: the frontier is blacklisted
  double progress_min_m = 0.2;       // getting this much closer counts as progress
  double blacklist_radius_m = 0.5;   // clusters whose target lies this close to a blacklisted one are skipped
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

// Frontier targets given up on.
class FrontierBlacklist {
 public:
  void add(Vec2 target) { points_.push_back(target); }
  bool contains(Vec2 p, double radius_m) const;
  size_t size() const { return points_.size(); }
  void clear() { points_.clear(); }

 private:
  std::vector<Vec2> points_;
};

// Progress of one robot toward one target: stalled() once it has not come progress_min_m closer
// within progress_timeout_s.
class ProgressWatch {
 public:
  void start(Vec2 target, Vec2 position, int64_t now_ns);
  bool stalled(Vec2 position, int64_t now_ns, const ExplorerConfig& config);
  Vec2 target() const { return target_; }

 private:
  Vec2 target_;
  double best_distance_ = 0.0;
  int64_t last_progress_ns_ = 0;
};

}  // namespace slam::planner

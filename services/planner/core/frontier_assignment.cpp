// Frontier assignment, blacklist and progress watch.
#include "planner/core/frontier_assignment.hpp"

#include <cmath>
#include <limits>
#include <queue>

namespace slam::planner {

Status validate(const ExplorerConfig& config) {
  if (config.min_cluster_cells == 0) return Error{"explore.min_cluster_cells must be at least 1"};
  if (!std::isfinite(config.gain_weight) || config.gain_weight < 0.0) {
    return Error{"explore.gain_weight must be a finite number >= 0"};
  }
  if (!std::isfinite(config.progress_timeout_s) || config.progress_timeout_s <= 0.0) {
    return Error{"explore.progress_timeout_s must be positive"};
  }
  if (!std::isfinite(config.progress_min_m) || config.progress_min_m <= 0.0) {
    return Error{"explore.progress_min_m must be positive"};
  }
  if (!std::isfinite(config.blacklist_radius_m) || config.blacklist_radius_m < 0.0) {
    return Error{"explore.blacklist_radius_m must be a finite number >= 0"};
  }
  if (!std::isfinite(config.blacklist_rest_s) || config.blacklist_rest_s < 0.0) {
    return Error{"explore.blacklist_rest_s must be a finite number >= 0"};
  }
  if (!std::isfinite(config.completion_grace_s) || config.completion_grace_s < 0.0) {
    return Error{"explore.completion_grace_s must be a finite number >= 0"};
  }
  if (!std::isfinite(config.retry_period_s) || config.retry_period_s <= 0.0) {
    return Error{"explore.retry_period_s must be positive"};
  }
  return Status::ok();
}

std::vector<FrontierAssignment> assign_frontiers(std::span<const ExploringRobot> robots,
                                                 std::span<const FrontierCluster> clusters,
                                                 std::span<const uint8_t> eligible, const PlanningGrid& grid,
                                                 double gain_weight, const PathCost& cost) {
  struct Candidate {
    double utility;  // exact when `exact`, otherwise an upper bound
    size_t robot;    // index into robots
    size_t cluster;
    double cost;
    bool exact;
    bool operator<(const Candidate& o) const { return utility < o.utility; }
  };
  std::priority_queue<Candidate> queue;
  for (size_t r = 0; r < robots.size(); ++r) {
    for (size_t c = 0; c < clusters.size(); ++c) {
      if (c < eligible.size() && eligible[c] == 0) continue;
      const double gain = gain_weight * clusters[c].size * grid.resolution();
      const double lower = distance(robots[r].position, grid.centre(clusters[c].target));
      queue.push(Candidate{gain - lower, r, c, lower, false});
    }
  }
  std::vector<bool> robot_done(robots.size(), false);
  std::vector<bool> cluster_done(clusters.size(), false);
  std::vector<FrontierAssignment> out;
  while (!queue.empty() && out.size() < robots.size()) {
    Candidate top = queue.top();
    queue.pop();
    if (robot_done[top.robot] || cluster_done[top.cluster]) continue;
    if (top.exact) {
      robot_done[top.robot] = true;
      cluster_done[top.cluster] = true;
      out.push_back(FrontierAssignment{robots[top.robot].robot, top.cluster,
                                       grid.centre(clusters[top.cluster].target), top.cost});
      continue;
    }
    const auto exact = cost(robots[top.robot].position, grid.centre(clusters[top.cluster].target));
    if (!exact) continue;  // unreachable from this robot
    const double gain = gain_weight * clusters[top.cluster].size * grid.resolution();
    queue.push(Candidate{gain - *exact, top.robot, top.cluster, *exact, true});
  }
  return out;
}

void FrontierBlacklist::add(Vec2 target, int64_t now_ns, int64_t rest_ns, double radius_m) {
  bool again = false;
  for (const Entry& e : entries_) again = again || distance(e.point, target) <= radius_m;
  entries_.push_back(Entry{target, again ? kForGood : now_ns + rest_ns});
}

bool FrontierBlacklist::contains(Vec2 p, double radius_m, int64_t now_ns) const {
  for (const Entry& e : entries_) {
    if (e.until_ns > now_ns && distance(p, e.point) <= radius_m) return true;
  }
  return false;
}

bool FrontierBlacklist::rests(Vec2 p, double radius_m, int64_t now_ns) const {
  bool resting = false;
  for (const Entry& e : entries_) {
    if (e.until_ns <= now_ns || distance(p, e.point) > radius_m) continue;
    if (e.until_ns == kForGood) return false;  // given up for good, whatever else rests here
    resting = true;
  }
  return resting;
}

void ProgressWatch::start(Vec2 target, int64_t now_ns) {
  target_ = target;
  best_remaining_ = std::numeric_limits<double>::infinity();
  last_progress_ns_ = now_ns;
}

bool ProgressWatch::stalled(double remaining_m, int64_t now_ns, const ExplorerConfig& config) {
  if (remaining_m <= best_remaining_ - config.progress_min_m) {
    best_remaining_ = remaining_m;
    last_progress_ns_ = now_ns;
    return false;
  }
  return static_cast<double>(now_ns - last_progress_ns_) > config.progress_timeout_s * 1e9;
}

}  // namespace slam::planner

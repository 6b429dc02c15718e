// Pass 5 of the traffic rules (traffic_rules.hpp), the leader rule (`clear_way`, on by default; not
// combined with one-way sections). The local passes step robots aside within yield_search_m; on a
// tree-like map (one way between two places, corridors one robot wide) a jam has no room near it.
// So the robot waiting longest, once clear_after_s, leads: its way ahead (clear_horizon_m) is its
// alone, robots about to enter it wait, and robots on it are pushed off the whole of its route into
// side room within clear_search_m (the furthest ahead the deepest), or on along the route when there
// is none. It leads until its route ends or changes, or until neither it nor a robot clearing its
// way has moved for clear_stall_s (then the others are tried first). This pass overrides the
// decisions of the leader, of the robots on its way and of those about to enter it.
// Invariant: one leader at a time, the longest wait first, so a robot's wait is bounded by the
// routes of the leaders that waited longer, unless a jam has no side room within clear_search_m
// (a stall, after which the lead passes on).
#include <algorithm>
#include <limits>

#include "planner/core/traffic_geometry.hpp"
#include "planner/core/traffic_rules.hpp"

namespace slam::planner {
namespace {

constexpr double kProgressM = 0.2;    // the leader moved this far: it makes progress
constexpr size_t kMaxPushes = 8;      // robots pushed per tick (the others on the way wait)
constexpr size_t kMaxDepthSlots = 2;  // robots a pushed robot leaves room for behind it

}  // namespace

bool TrafficRules::keeps_apart(std::span<const TrafficRobot> robots, size_t i, Vec2 to) const {
  const double reach = this->reach();
  const Vec2 from = robots[i].position;
  for (size_t k = 0; k < robots.size(); ++k) {
    if (k == i) continue;
    const Vec2 other = robots[k].position;
    if (distance_to_segment(other, from, to) < std::min(reach, distance(other, from)) - 1e-6) return false;
  }
  return std::none_of(committed_.begin(), committed_.end(),
                      [&](Vec2 p) { return distance_to_segment(p, from, to) < reach; });
}

bool TrafficRules::keep_leader(std::span<const TrafficRobot> robots, int64_t now_ns) {
  const auto l = static_cast<size_t>(leader_);
  if (l >= robots.size() || robots[l].ahead.empty() || robots[l].route_since_ns != leader_route_ns_)
    return false;
  const Vec2 at = robots[l].position;
  if (distance(at, leader_progress_at_) > kProgressM) {
    leader_progress_at_ = at;
    leader_progress_ns_ = now_ns;
  }
  if (static_cast<double>(now_ns - leader_progress_ns_) * 1e-9 > config_.clear_stall_s) {
    stalled_[l] = 1;  // its way could not be cleared: the others first
    return false;
  }
  return true;
}

void TrafficRules::choose_leader(std::span<const TrafficRobot> robots, int64_t now_ns,
                                 const std::vector<TrafficDecision>& decisions) {
  const auto after = static_cast<int64_t>(config_.clear_after_s * 1e9);
  const auto due = [&](uint32_t i) {
    const TrafficDecision& d = decisions[i];
    // A wait before a one-way section is bounded by the section rule already.
    return d.order != TrafficOrder::Go && !d.section && d.waiting_since_ns >= 0 &&
           now_ns - d.waiting_since_ns >= after;
  };
  // The robot waiting longest: its wait counts on across new routes (a robot given a new goal while
  // held ranks last by route age, but its wait goes on). One whose way could not be cleared is tried
  // again once every other one due has been tried, or once it has moved.
  for (size_t i = 0; i < robots.size(); ++i)
    if (decisions[i].waiting_since_ns < 0) stalled_[i] = 0;
  int32_t chosen = -1;
  for (int pass = 0; pass < 2 && chosen < 0; ++pass) {
    for (const uint32_t i : order_)
      if (due(i) && !stalled_[i] &&
          (chosen < 0 ||
           decisions[i].waiting_since_ns < decisions[static_cast<size_t>(chosen)].waiting_since_ns))
        chosen = static_cast<int32_t>(i);
    if (chosen < 0) std::fill(stalled_.begin(), stalled_.end(), 0);
  }
  if (chosen < 0) return;
  const TrafficRobot& r = robots[static_cast<size_t>(chosen)];
  leader_ = chosen;
  leader_route_ns_ = r.route_since_ns;
  leader_progress_at_ = r.position;
  leader_progress_ns_ = now_ns;
  ++clearings_;
}

void TrafficRules::clear_way(const PlanningGrid& grid, Robots robots, int64_t now_ns, Decisions& decisions) {
  const size_t n = robots.size();
  pushed_.resize(n, 0);
  pushed_from_.resize(n);
  stalled_.resize(n, 0);
  push_depth_.resize(n, 0.0);
  // The longest way the leader can have (reserved here so a new leader allocates nothing).
  size_t longest = 0;
  for (const TrafficRobot& r : robots) longest = std::max(longest, r.ahead.size());
  way_points_.reserve(2 * (longest + 2));
  push_order_.reserve(n);
  committed_.reserve(n);
  committed_.clear();
  if (leader_ >= 0 && !keep_leader(robots, now_ns)) {
    leader_ = -1;
    std::fill(pushed_.begin(), pushed_.end(), 0);
  }
  if (leader_ < 0) choose_leader(robots, now_ns, decisions);
  if (leader_ < 0) return;
  // Robots on the first clear_horizon_m of its way are pushed, and off the whole of it: on a tree a
  // robot left further along the way would only be met again.
  const TrafficRobot& leader = robots[static_cast<size_t>(leader_)];
  way_points_.clear();
  append_way(leader, std::numeric_limits<double>::infinity(), way_points_);
  const size_t route_end = way_points_.size();
  append_way(leader, config_.clear_horizon_m, way_points_);
  const std::span<const Vec2> all(way_points_);
  find_robots_on_way(robots, all.subspan(route_end), decisions);
  const bool stuck = push_off_way(grid, robots, all.first(route_end), now_ns, decisions);
  committed_.clear();  // the local rules' searches (next tick) see bodies only
  lead(robots, stuck, decisions);
}

void TrafficRules::find_robots_on_way(Robots robots, std::span<const Vec2> way, Decisions& decisions) {
  const auto l = static_cast<size_t>(leader_);
  const double reach = this->reach();
  // Who is on the way and who is about to enter it. A robot driving along it away from the leader
  // clears it by itself and goes on; a pushed robot stays pushed (off the way, it goes deeper).
  push_order_.clear();
  for (size_t k = 0; k < robots.size(); ++k) {
    if (k == l) continue;
    TrafficDecision& d = decisions[k];
    const Vec2 at = robots[k].position;
    const bool on_way = traffic::gap_to(way, at) < reach + traffic::kYieldMarginM;
    if (on_way && !pushed_[k] && d.order == TrafficOrder::Go && !robots[k].ahead.empty() &&
        !opposed(claim(k), way, reach))
      continue;
    if (on_way || pushed_[k]) {
      // Robots already off the way first (deepest in), then from the far end of the way back.
      push_order_.emplace_back(on_way ? traffic::along(way, at) : config_.clear_horizon_m + 1.0,
                               static_cast<uint32_t>(k));
    } else if (!robots[k].ahead.empty() && near(claim(k), way, reach)) {
      d.order = TrafficOrder::Wait;
      d.hold = at;
      d.blocker = leader_;
      d.deadlock = d.section = false;
    }
  }
  std::sort(push_order_.begin(), push_order_.end(), std::greater<>());
}

bool TrafficRules::push_off_way(const PlanningGrid& grid, Robots robots, std::span<const Vec2> route,
                                int64_t now_ns, Decisions& decisions) {
  const TrafficRobot& leader = robots[static_cast<size_t>(leader_)];
  const double reach = this->reach();
  size_t on_way_behind =
      static_cast<size_t>(std::count_if(push_order_.begin(), push_order_.end(),
                                        [&](const auto& e) { return e.first <= config_.clear_horizon_m; }));
  bool stuck = false;  // a robot on the way has no room off it
  for (size_t at = 0; at < push_order_.size(); ++at) {
    const auto [s, k] = push_order_[at];
    TrafficDecision& d = decisions[k];
    d.blocker = leader_;
    d.deadlock = d.section = false;
    if (s <= config_.clear_horizon_m) --on_way_behind;
    if (!pushed_[k]) {
      // Room for the robots behind it on the way, which may follow it into the same branch.
      pushed_[k] = 1;
      pushed_from_[k] = robots[k].position;
      push_depth_[k] = 2.0 * reach * static_cast<double>(std::min(on_way_behind, kMaxDepthSlots));
    }
    // After a robot that can go nowhere the rest wait too: a tick searches at most once in vain.
    const bool searched = at < kMaxPushes && !stuck;
    Vec2 step;
    bool go = searched && find_yield(grid, robots, k, route, step, config_.clear_search_m, push_depth_[k]) &&
              keeps_apart(robots, k, step);
    if (!go && searched && s <= config_.clear_horizon_m) {
      // No side room within reach: it drives on along the leader's route ahead of it (the "push"),
      // towards the next branch, unless the route ends there (a dead end: stuck) or a body is in
      // the way (a robot further on, pushed too: it waits for it to move).
      const double along = traffic::along(route, robots[k].position);
      step = point_along(leader, along + config_.yield_step_m);
      if (distance(step, robots[k].position) < kProgressM / 4.0) {
        stuck = true;
      } else {
        // Straight to a point ahead on the route can clip a corner from where the robot stands:
        // then back onto the route first.
        bool off_walls = traffic::keeps_off_walls(grid, robots[k].position, step, config_.robot_radius_m);
        if (!off_walls) {
          step = point_along(leader, along);
          off_walls = traffic::keeps_off_walls(grid, robots[k].position, step, config_.robot_radius_m);
        }
        go = off_walls && keeps_apart(robots, k, step);
      }
    }
    if (go) {
      d.order = TrafficOrder::Yield;
      d.hold = step;
      committed_.push_back(step);
      // Clearing is under way while the robots sent off the way move: the leader waiting for them
      // is not stalled (a robot sent but not moving, held by a wall or a robot, is no progress
      // however often it is sent).
      if (distance(robots[k].position, pushed_from_[k]) > kProgressM) {
        pushed_from_[k] = robots[k].position;
        leader_progress_ns_ = now_ns;
      }
    } else {
      d.order = TrafficOrder::Wait;
      d.hold = robots[k].position;
      stuck = stuck || (!searched && s <= config_.clear_horizon_m);
    }
  }
  return stuck;
}

void TrafficRules::lead(Robots robots, bool stuck, Decisions& decisions) {
  // The leader goes unless a body stands close ahead of it (the others keep off its way) or a robot
  // on its way has nowhere to go yet (driving up to it would only close the room left).
  const auto l = static_cast<size_t>(leader_);
  int32_t body = stuck ? static_cast<int32_t>(push_order_.back().second) : -1;
  for (size_t k = 0; k < robots.size() && body < 0; ++k)
    if (k != l && body_ahead(robots, l, k)) body = static_cast<int32_t>(k);
  TrafficDecision& d = decisions[l];
  d.deadlock = d.section = false;
  d.blocker = body;
  d.order = body < 0 ? TrafficOrder::Go : TrafficOrder::Wait;
  d.hold = robots[l].position;
}

}  // namespace slam::planner

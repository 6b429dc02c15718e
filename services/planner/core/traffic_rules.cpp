// The traffic rules (traffic_rules.hpp): their options, the passes in order and what the passes
// share (ways along the routes, polyline tests). The passes themselves live in their own units.
#include "planner/core/traffic_rules.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "planner/core/traffic_geometry.hpp"

namespace slam::planner {
namespace {

using traffic::gap_to;
using traffic::segment_gap;

bool finite_positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

Status validate(const CoordinationConfig& c) {
  if (!finite_positive(c.robot_radius_m)) return Error{"coordination.robot_radius_m must be positive"};
  if (!std::isfinite(c.clearance_m) || c.clearance_m < 0.0)
    return Error{"coordination.clearance_m must be zero or more"};
  if (!finite_positive(c.lookahead_m)) return Error{"coordination.lookahead_m must be positive"};
  if (!finite_positive(c.body_lookahead_m) || c.body_lookahead_m > c.lookahead_m)
    return Error{"coordination.body_lookahead_m must be positive and at most lookahead_m"};
  if (!finite_positive(c.yield_search_m) || c.yield_search_m > 20.0)
    return Error{"coordination.yield_search_m must be in (0, 20]"};
  if (!finite_positive(c.yield_step_m)) return Error{"coordination.yield_step_m must be positive"};
  if (!finite_positive(c.replan_after_s)) return Error{"coordination.replan_after_s must be positive"};
  if (!finite_positive(c.section_horizon_m)) return Error{"coordination.section_horizon_m must be positive"};
  if (!std::isfinite(c.clear_horizon_m) || c.clear_horizon_m < c.lookahead_m)
    return Error{"coordination.clear_horizon_m must be at least lookahead_m"};
  if (!finite_positive(c.clear_after_s)) return Error{"coordination.clear_after_s must be positive"};
  if (!finite_positive(c.clear_search_m) || c.clear_search_m > 20.0)
    return Error{"coordination.clear_search_m must be in (0, 20]"};
  if (!finite_positive(c.clear_stall_s)) return Error{"coordination.clear_stall_s must be positive"};
  return Status::ok();
}

void TrafficRules::decide(const PlanningGrid& grid, Robots robots, int64_t now_ns, Decisions& decisions) {
  decisions.resize(robots.size());
  rank(robots);
  plan_sections(grid, robots);
  reserve(grid, robots, decisions);
  resolve_deadlocks(grid, robots, decisions);
  if (leader_rule_on()) clear_way(grid, robots, now_ns, decisions);
  note_waits(robots, now_ns, decisions);
}

// Pass 1. Invariant: the earlier route ranks first (ties by a number every planner gives the robot
// alike), so a waiting robot only rises while new routes rank below it, and no robot without a
// route is ranked (it reserves nothing).
void TrafficRules::rank(Robots robots) {
  order_.clear();
  for (size_t i = 0; i < robots.size(); ++i)
    if (!robots[i].ahead.empty()) order_.push_back(static_cast<uint32_t>(i));
  std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
    return std::tie(robots[a].route_since_ns, robots[a].tie, a) <
           std::tie(robots[b].route_since_ns, robots[b].tie, b);
  });
}

void TrafficRules::note_waits(Robots robots, int64_t now_ns, Decisions& decisions) {
  for (size_t i = 0; i < robots.size(); ++i) {
    TrafficDecision& d = decisions[i];
    const bool waiting = d.order != TrafficOrder::Go && !robots[i].ahead.empty();
    if (!waiting) {
      d.waiting_since_ns = -1;
    } else if (d.waiting_since_ns < 0) {
      d.waiting_since_ns = now_ns;
    }
  }
}

void TrafficRules::append_way(const TrafficRobot& robot, double length, std::vector<Vec2>& out) {
  out.push_back(robot.position);
  double walked = 0.0;
  Vec2 last = robot.position;
  for (const Vec2& p : robot.ahead) {
    const double seg = distance(last, p);
    if (walked + seg >= length) {
      if (seg > 0.0) out.push_back(last + (p - last) * ((length - walked) / seg));
      return;
    }
    out.push_back(p);
    walked += seg;
    last = p;
  }
}

Vec2 TrafficRules::point_along(const TrafficRobot& robot, double length) {
  double walked = 0.0;
  Vec2 last = robot.position;
  for (const Vec2& p : robot.ahead) {
    const double seg = distance(last, p);
    if (walked + seg >= length) return seg > 0.0 ? last + (p - last) * ((length - walked) / seg) : p;
    walked += seg;
    last = p;
  }
  return last;
}

bool TrafficRules::near(std::span<const Vec2> a, std::span<const Vec2> b, double gap) {
  if (a.size() == 1) return gap_to(b, a[0]) < gap;
  if (b.size() == 1) return gap_to(a, b[0]) < gap;
  for (size_t i = 1; i < a.size(); ++i)
    for (size_t j = 1; j < b.size(); ++j)
      if (segment_gap(a[i - 1], a[i], b[j - 1], b[j]) < gap) return true;
  return false;
}

bool TrafficRules::opposed(std::span<const Vec2> a, std::span<const Vec2> b, double gap) {
  constexpr double kOppositeCos = -0.5;  // headings more than 120 degrees apart
  for (size_t i = 1; i < a.size(); ++i) {
    const Vec2 da = a[i] - a[i - 1];
    const double la = norm(da);
    if (la <= 0.0) continue;
    for (size_t j = 1; j < b.size(); ++j) {
      const Vec2 db = b[j] - b[j - 1];
      const double lb = norm(db);
      if (lb > 0.0 && dot(da, db) < kOppositeCos * la * lb &&
          segment_gap(a[i - 1], a[i], b[j - 1], b[j]) < gap)
        return true;
    }
  }
  return false;
}

}  // namespace slam::planner

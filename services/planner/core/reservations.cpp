// Pass 3 of the traffic rules (traffic_rules.hpp), reservations and bodies. In rank order each
// moving robot reserves the first lookahead_m of its way (a robot kept out of a section: up to its
// waiting place), as wide as two robots plus the clearance.
// Invariant: a robot is granted its reservation only when it keeps `reach` from every reservation
// granted before it (ranked higher) and no body stands close ahead of it; otherwise it waits where
// it was told to stay, or, standing on the reservation it gives way to, steps aside off it.
#include <algorithm>

#include "planner/core/traffic_geometry.hpp"
#include "planner/core/traffic_rules.hpp"

namespace slam::planner {

void TrafficRules::build_claim(size_t i, const TrafficRobot& robot, double length) {
  claim_at_[2 * i] = static_cast<uint32_t>(claim_points_.size());
  append_way(robot, length, claim_points_);
  claim_at_[2 * i + 1] = static_cast<uint32_t>(claim_points_.size());
}

std::span<const Vec2> TrafficRules::claim(size_t i) const {
  return {claim_points_.data() + claim_at_[2 * i], claim_at_[2 * i + 1] - claim_at_[2 * i]};
}

bool TrafficRules::body_ahead(Robots robots, size_t i, size_t k) const {
  // A body ahead stops the robot; one it moves away from does not (they part).
  const double now_gap = distance(robots[i].position, robots[k].position);
  const double gap = traffic::gap_to_prefix(claim(i), config_.body_lookahead_m, robots[k].position);
  return gap < reach() && gap < now_gap - 1e-6;
}

void TrafficRules::reserve(const PlanningGrid& grid, Robots robots, Decisions& decisions) {
  const size_t n = robots.size();
  const double reach = this->reach();
  // A robot kept out of a section reserves its way only up to where it waits, `reach` before the
  // mouth, leaving the mouth to the robots coming out.
  claim_points_.clear();
  claim_at_.resize(2 * n);
  for (size_t i = 0; i < n; ++i)
    build_claim(
        i, robots[i],
        section_blocker_[i] < 0 ? config_.lookahead_m : std::min(config_.lookahead_m, section_wait_m(i)));
  granted_.assign(n, 0);
  const double far = 2.0 * config_.lookahead_m + reach;  // no two reservations of robots further apart meet

  // Every robot starts the tick free to go; what it was told last tick is kept in prior_ (and
  // whether it broke a cycle, for pass 4).
  was_deadlocked_.resize(n);
  prior_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    TrafficDecision& d = decisions[i];
    prior_[i] = d;
    was_deadlocked_[i] = d.deadlock ? 1 : 0;
    d = TrafficDecision{TrafficOrder::Go, robots[i].position, -1, d.waiting_since_ns, false, false};
    // Keep the place a waiting robot was told to stay at, so it does not creep (one that was driving
    // up to a section's mouth stops where it is when something else holds it).
    if (prior_[i].order == TrafficOrder::Wait && !prior_[i].section) d.hold = prior_[i].hold;
  }

  for (const uint32_t i : order_) {
    const TrafficRobot& me = robots[i];
    const auto mine = claim(i);
    int32_t blocker = -1;
    for (size_t k = 0; k < n && blocker < 0; ++k) {
      if (k == i || distance(me.position, robots[k].position) > far) continue;
      if ((granted_[k] && near(mine, claim(k), reach)) || body_ahead(robots, i, k))
        blocker = static_cast<int32_t>(k);
    }
    TrafficDecision& d = decisions[i];
    if (blocker < 0) {
      granted_[i] = 1;
      d.order = TrafficOrder::Go;
      if (section_blocker_[i] >= 0) {
        // Kept out of the section: drives up to its waiting place; one already held (waiting, or
        // stepped aside for someone) stays where it was told.
        d.order = TrafficOrder::Wait;
        d.section = true;
        d.blocker = section_blocker_[i];
        const TrafficDecision& prior = prior_[i];
        if (prior.order == TrafficOrder::Go) {
          d.hold = point_along(me, section_wait_m(i));
        } else if (prior.order == TrafficOrder::Wait && prior.section) {
          d.hold = prior.hold;
        }
      }
      continue;
    }
    d.blocker = blocker;
    if (granted_[static_cast<size_t>(blocker)] &&
        traffic::gap_to(claim(static_cast<size_t>(blocker)), me.position) < reach) {
      // Standing on the way of a robot that goes first: step aside.
      yield(grid, robots, i, static_cast<size_t>(blocker), decisions);
    } else {
      d.order = TrafficOrder::Wait;
    }
  }
}

}  // namespace slam::planner

// The traffic rules (TrafficRules, declared in fleet_coordinator.hpp): reservations ahead of each
// robot, who waits for whom, deadlock resolution and the places where a robot steps aside.
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "planner/core/fleet_coordinator.hpp"
#include "planner/core/line_of_sight.hpp"
#include "planner/core/traffic_geometry.hpp"

namespace slam::planner {
namespace {

using traffic::gap_to;
using traffic::gap_to_prefix;
using traffic::kYieldMarginM;
using traffic::segment_gap;

bool finite_positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

Status validate(const CoordinationConfig& c) {
  if (!finite_positive(c.robot_radius_m)) return Error{"coordination robot_radius_m must be positive"};
  if (!std::isfinite(c.clearance_m) || c.clearance_m < 0.0)
    return Error{"coordination clearance_m must be zero or more"};
  if (!finite_positive(c.lookahead_m)) return Error{"coordination lookahead_m must be positive"};
  if (!finite_positive(c.body_lookahead_m) || c.body_lookahead_m > c.lookahead_m)
    return Error{"coordination body_lookahead_m must be positive and at most lookahead_m"};
  if (!finite_positive(c.yield_search_m) || c.yield_search_m > 20.0)
    return Error{"coordination yield_search_m must be in (0, 20]"};
  if (!finite_positive(c.yield_step_m)) return Error{"coordination yield_step_m must be positive"};
  if (!finite_positive(c.replan_after_s)) return Error{"coordination replan_after_s must be positive"};
  if (!finite_positive(c.section_horizon_m)) return Error{"coordination section_horizon_m must be positive"};
  if (!std::isfinite(c.clear_horizon_m) || c.clear_horizon_m < c.lookahead_m)
    return Error{"coordination clear_horizon_m must be at least lookahead_m"};
  if (!finite_positive(c.clear_after_s)) return Error{"coordination clear_after_s must be positive"};
  if (!finite_positive(c.clear_search_m) || c.clear_search_m > 20.0)
    return Error{"coordination clear_search_m must be in (0, 20]"};
  if (!finite_positive(c.clear_stall_s)) return Error{"coordination clear_stall_s must be positive"};
  return Status::ok();
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

bool TrafficRules::narrow_at(const PlanningGrid& grid, Vec2 p, Vec2 along) const {
  const Vec2 side{-along.y, along.x};
  const double room = reach() + kYieldMarginM;
  const double step = grid.resolution();
  for (const double sign : {1.0, -1.0}) {
    bool open = true;
    for (double t = step; t <= room && open; t += step) {
      const auto c = grid.cell_at(p + side * (sign * t));
      open = c && !grid.blocked(*c);
    }
    if (open) return false;
  }
  return true;
}

void TrafficRules::build_section(const PlanningGrid& grid, size_t i, const TrafficRobot& robot) {
  section_at_[2 * i] = section_at_[2 * i + 1] = static_cast<uint32_t>(section_points_.size());
  entry_m_[i] = std::numeric_limits<double>::infinity();
  if (!config_.one_way_sections || robot.ahead.empty() || grid.empty()) return;
  // Samples every cell along the way: the first narrow one within the lookahead opens the section,
  // the first open one after it (or the horizon) closes it.
  const double step = grid.resolution();
  double walked = 0.0, next_sample = 0.0;
  bool inside = false;
  Vec2 from = robot.position;
  for (const Vec2& to : robot.ahead) {
    const double seg = distance(from, to);
    if (seg <= 0.0) continue;
    const Vec2 along = (to - from) * (1.0 / seg);
    for (; next_sample <= walked + seg; next_sample += step) {
      const Vec2 p = from + along * (next_sample - walked);
      if (!inside) {
        if (next_sample > config_.lookahead_m) return;
        if (!narrow_at(grid, p, along)) continue;
        inside = true;
        entry_m_[i] = next_sample;
        section_points_.push_back(p);
      } else if (!narrow_at(grid, p, along) || next_sample - entry_m_[i] > config_.section_horizon_m) {
        section_points_.push_back(p);
        section_at_[2 * i + 1] = static_cast<uint32_t>(section_points_.size());
        return;
      }
    }
    if (inside) section_points_.push_back(to);
    walked += seg;
    from = to;
  }
  section_at_[2 * i + 1] = static_cast<uint32_t>(section_points_.size());
}

std::span<const Vec2> TrafficRules::section(size_t i) const {
  return {section_points_.data() + section_at_[2 * i], section_at_[2 * i + 1] - section_at_[2 * i]};
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

void TrafficRules::grant_sections(std::span<const TrafficRobot> robots) {
  const size_t n = robots.size();
  const double reach = this->reach();
  // Inside: on the narrow stretch already, or at its mouth with the section granted (it may be
  // entering). Such a robot cannot turn back, so it keeps the section whatever its priority.
  const auto inside = [&](uint32_t i) {
    return entry_m_[i] <= 0.0 || (section_held_[i] && entry_m_[i] <= reach);
  };
  section_order_.clear();
  for (const uint32_t i : order_)
    if (section(i).size() >= 2 && inside(i)) section_order_.push_back(i);
  for (const uint32_t i : order_)
    if (section(i).size() >= 2 && !inside(i)) section_order_.push_back(i);
  section_blocker_.assign(n, -1);
  for (size_t at = 0; at < section_order_.size(); ++at) {
    const uint32_t i = section_order_[at];
    if (inside(i)) continue;
    // Against every robot granted before it, and every higher-priority one still waiting to enter:
    // a stream one way does not starve a robot waiting to go the other way.
    for (size_t before = 0; before < at; ++before) {
      const uint32_t k = section_order_[before];
      if (opposed(section(i), section(k), reach)) {
        section_blocker_[i] = static_cast<int32_t>(k);
        break;
      }
    }
  }
  section_held_.assign(n, 0);
  for (const uint32_t i : section_order_) section_held_[i] = section_blocker_[i] < 0 ? 1 : 0;
}

void TrafficRules::build_claim(size_t i, const TrafficRobot& robot, double length) {
  claim_at_[2 * i] = static_cast<uint32_t>(claim_points_.size());
  append_way(robot, length, claim_points_);
  claim_at_[2 * i + 1] = static_cast<uint32_t>(claim_points_.size());
}

std::span<const Vec2> TrafficRules::claim(size_t i) const {
  return {claim_points_.data() + claim_at_[2 * i], claim_at_[2 * i + 1] - claim_at_[2 * i]};
}

bool TrafficRules::near(std::span<const Vec2> a, std::span<const Vec2> b, double gap) {
  if (a.size() == 1) return gap_to(b, a[0]) < gap;
  if (b.size() == 1) return gap_to(a, b[0]) < gap;
  for (size_t i = 1; i < a.size(); ++i)
    for (size_t j = 1; j < b.size(); ++j)
      if (segment_gap(a[i - 1], a[i], b[j - 1], b[j]) < gap) return true;
  return false;
}

void TrafficRules::decide(const PlanningGrid& grid, std::span<const TrafficRobot> robots, int64_t now_ns,
                          std::vector<TrafficDecision>& decisions) {
  const size_t n = robots.size();
  decisions.resize(n);
  order_.clear();
  for (size_t i = 0; i < n; ++i)
    if (!robots[i].ahead.empty()) order_.push_back(static_cast<uint32_t>(i));
  std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
    return std::tie(robots[a].route_since_ns, robots[a].tie, a) <
           std::tie(robots[b].route_since_ns, robots[b].tie, b);
  });

  section_points_.clear();
  section_at_.resize(2 * n);
  entry_m_.resize(n);
  section_held_.resize(n, 0);
  for (size_t i = 0; i < n; ++i) build_section(grid, i, robots[i]);
  grant_sections(robots);
  const double reach = this->reach();

  // A robot kept out of a section reserves its way only up to where it waits, `reach` before the
  // mouth, leaving the mouth to the robots coming out.
  const auto wait_at = [&](size_t i) { return std::max(0.0, entry_m_[i] - reach); };
  claim_points_.clear();
  claim_at_.resize(2 * n);
  for (size_t i = 0; i < n; ++i)
    build_claim(i, robots[i],
                section_blocker_[i] < 0 ? config_.lookahead_m : std::min(config_.lookahead_m, wait_at(i)));
  granted_.assign(n, 0);
  const double far = 2.0 * config_.lookahead_m + reach;  // no two reservations of robots further apart meet

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
      if (granted_[k] && near(mine, claim(k), reach)) {
        blocker = static_cast<int32_t>(k);
        continue;
      }
      // A body ahead stops the robot; one it moves away from does not (they part).
      const double now_gap = distance(me.position, robots[k].position);
      const double gap = gap_to_prefix(mine, config_.body_lookahead_m, robots[k].position);
      if (gap < reach && gap < now_gap - 1e-6) blocker = static_cast<int32_t>(k);
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
          d.hold = point_along(me, wait_at(i));
        } else if (prior.order == TrafficOrder::Wait && prior.section) {
          d.hold = prior.hold;
        }
      }
      continue;
    }
    d.blocker = blocker;
    if (granted_[static_cast<size_t>(blocker)] &&
        gap_to(claim(static_cast<size_t>(blocker)), me.position) < reach) {
      // Standing on the way of a robot that goes first: step aside.
      yield(grid, robots, i, static_cast<size_t>(blocker), decisions);
    } else {
      d.order = TrafficOrder::Wait;
    }
  }
  resolve_deadlocks(grid, robots, decisions);
  clear_way(grid, robots, now_ns, decisions);

  for (size_t i = 0; i < n; ++i) {
    TrafficDecision& d = decisions[i];
    const bool waiting = d.order != TrafficOrder::Go && !robots[i].ahead.empty();
    if (!waiting) {
      d.waiting_since_ns = -1;
    } else if (d.waiting_since_ns < 0) {
      d.waiting_since_ns = now_ns;
    }
  }
}

void TrafficRules::resolve_deadlocks(const PlanningGrid& grid, std::span<const TrafficRobot> robots,
                                     std::vector<TrafficDecision>& decisions) {
  const size_t n = robots.size();
  visit_.assign(n, 0);
  waited_by_.resize(n);
  uint32_t walk = 0;
  for (size_t s = 0; s < n; ++s) {
    if (decisions[s].order != TrafficOrder::Wait || visit_[s] != 0) continue;
    ++walk;
    size_t cur = s, prev = s;
    // Follow who waits for whom until the chain ends, meets an earlier walk or closes on itself.
    while (visit_[cur] == 0) {
      visit_[cur] = walk;
      if (decisions[cur].order != TrafficOrder::Wait || decisions[cur].blocker < 0) break;
      prev = cur;
      cur = static_cast<size_t>(decisions[cur].blocker);
    }
    if (visit_[cur] != walk) continue;  // joined a chain already handled
    if (decisions[cur].order == TrafficOrder::Wait && decisions[cur].blocker >= 0 &&
        visit_[static_cast<size_t>(decisions[cur].blocker)] == walk && cur != prev) {
      // A cycle through cur: its lowest-priority member gives way to the robot it waits for; when it
      // has nowhere to go, the next lowest does.
      cycle_.clear();
      size_t k = cur;
      do {
        cycle_.push_back(static_cast<uint32_t>(k));
        k = static_cast<size_t>(decisions[k].blocker);
      } while (k != cur);
      // The one already stepping aside for this cycle carries on (switching roles midway would send
      // them past each other); then a robot waiting before a section: it stands where there is room,
      // and the one inside it cannot clear the section by stepping aside (the section stays its
      // own); otherwise the highest tie number first: a number every planner gives the robot alike,
      // so planners that each drive one robot of the cycle agree on who moves.
      for (const uint32_t m : cycle_) waited_by_[static_cast<size_t>(decisions[m].blocker)] = m;
      std::sort(cycle_.begin(), cycle_.end(), [&](uint32_t a, uint32_t b) {
        return std::tuple(was_deadlocked_[a], decisions[a].section, robots[a].tie, a) >
               std::tuple(was_deadlocked_[b], decisions[b].section, robots[b].tie, b);
      });
      // The same cycle stays until the yielding robot is out of the way: counted once.
      if (std::none_of(cycle_.begin(), cycle_.end(), [&](uint32_t m) { return was_deadlocked_[m] != 0; }))
        ++deadlocks_;
      // A member steps off the way of the robot waiting for it: that breaks the cycle's edge into
      // it (off the way of the one it waits for would not, unless the two wait for each other).
      bool moved = false;
      for (const uint32_t m : cycle_) {
        yield(grid, robots, m, waited_by_[m], decisions);
        decisions[m].deadlock = true;
        moved = decisions[m].order == TrafficOrder::Yield;
        if (moved) break;
      }
      if (!moved) back_off(grid, robots, decisions);
    } else if (robots[cur].ahead.empty() && cur != prev && decisions[cur].order == TrafficOrder::Go) {
      // The chain ends at a stopped robot: it steps off the way of the one waiting for it.
      yield(grid, robots, cur, prev, decisions);
    }
  }
}

void TrafficRules::back_off(const PlanningGrid& grid, std::span<const TrafficRobot> robots,
                            std::vector<TrafficDecision>& decisions) {
  // No member of the cycle has room to step aside: the robots queued behind them fill the way
  // back. The robots queued behind a member step off the way of the robot that member gives way
  // to, the nearest first, then the ones behind them: room opens behind the member from the end of
  // its queue, and the member backs into it on a later tick.
  constexpr size_t kMaxBackOff = 16;  // robots tried per cycle and tick
  back_off_.clear();
  for (const uint32_t m : cycle_) back_off_.emplace_back(m, waited_by_[m]);
  for (size_t at = 0; at < back_off_.size() && at < kMaxBackOff; ++at) {
    const auto [front, away] = back_off_[at];
    for (size_t q = 0; q < robots.size(); ++q) {
      if (q == away || decisions[q].order != TrafficOrder::Wait ||
          decisions[q].blocker != static_cast<int32_t>(front) ||
          std::find(cycle_.begin(), cycle_.end(), static_cast<uint32_t>(q)) != cycle_.end())
        continue;
      yield(grid, robots, q, away, decisions);
      decisions[q].deadlock = true;
      if (decisions[q].order == TrafficOrder::Yield) return;
      back_off_.emplace_back(static_cast<uint32_t>(q), away);
    }
  }
}

void TrafficRules::yield(const PlanningGrid& grid, std::span<const TrafficRobot> robots, size_t i, size_t to,
                         std::vector<TrafficDecision>& decisions) {
  // Off the way the other robot will drive, somewhat beyond its reservation.
  long_points_.clear();
  append_way(robots[to], config_.lookahead_m + config_.yield_search_m, long_points_);
  TrafficDecision& d = decisions[i];
  d.blocker = static_cast<int32_t>(to);
  Vec2 step;
  if (find_yield(grid, robots, i, long_points_, step, config_.yield_search_m)) {
    d.order = TrafficOrder::Yield;
    d.hold = step;
  } else {
    d.order = TrafficOrder::Wait;  // nowhere to go: it stays and the other one waits for it
    d.hold = robots[i].position;
  }
}

bool TrafficRules::find_yield(const PlanningGrid& grid, std::span<const TrafficRobot> robots, size_t i,
                              std::span<const Vec2> away, Vec2& step, double search_m, double depth) {
  if (grid.empty()) return false;
  const Vec2 start = robots[i].position;
  const auto start_cell = grid.cell_at(start);
  if (!start_cell) return false;
  const double reach = this->reach();
  const double body = 2.0 * config_.robot_radius_m;
  // Only the robots within reach of the search area can be in the way (listed once, not per cell).
  nearby_.reserve(2 * robots.size());
  nearby_.clear();
  for (size_t k = 0; k < robots.size(); ++k)
    if (k != i && distance(robots[k].position, start) < search_m + 2.0 * reach)
      nearby_.push_back(robots[k].position);
  // Places other robots were sent to this tick count as bodies too (two robots sent the same way).
  nearby_.insert(nearby_.end(), committed_.begin(), committed_.end());
  const auto clear_of_bodies = [&](Vec2 p, double gap) {
    return std::none_of(nearby_.begin(), nearby_.end(), [&](Vec2 other) { return distance(other, p) < gap; });
  };
  const size_t cells = grid.geometry().cells();
  if (seen_stamp_.size() != cells) {
    seen_stamp_.assign(cells, 0);
    parent_.assign(cells, 0);
    queue_.reserve(cells);  // a search of any radius then allocates nothing
    stamp_ = 0;
  }
  if (++stamp_ == 0) {
    std::fill(seen_stamp_.begin(), seen_stamp_.end(), 0);
    stamp_ = 1;
  }
  queue_.clear();
  const auto first = static_cast<uint32_t>(grid.index(*start_cell));
  seen_stamp_[first] = stamp_;
  parent_[first] = first;
  queue_.push_back(first);
  // The nearest place `depth` off the way; the nearest one off it at all when there is none.
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  uint32_t found = kNone, shallow = kNone;
  for (size_t head = 0; head < queue_.size(); ++head) {
    const uint32_t at = queue_[head];
    const Cell c = grid.cell_of(at);
    const Vec2 centre = grid.centre(c);
    const double off = gap_to(away, centre);
    if (off >= reach + kYieldMarginM && (shallow == kNone || off >= reach + kYieldMarginM + depth) &&
        clear_of_bodies(centre, reach)) {
      if (shallow == kNone) shallow = at;
      if (off >= reach + kYieldMarginM + depth) {
        found = at;
        break;
      }
    }
    constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const Cell nb{c.x + kDx[k], c.y + kDy[k]};
      if (!grid.contains(nb)) continue;
      const auto idx = static_cast<uint32_t>(grid.index(nb));
      if (seen_stamp_[idx] == stamp_ || grid.impassable(nb, UnknownPolicy::Blocked)) continue;
      const Vec2 p = grid.centre(nb);
      // Never squeeze past another robot on the way.
      if (distance(p, start) > search_m || !clear_of_bodies(p, reach)) continue;
      seen_stamp_[idx] = stamp_;
      parent_[idx] = at;
      queue_.push_back(idx);
    }
  }
  if (found == kNone) found = shallow;
  if (found == kNone) return false;
  // The furthest cell of the way there that is in sight and within one yield step.
  step = grid.centre(grid.cell_of(found));
  for (uint32_t at = found;; at = parent_[at]) {
    const Vec2 p = grid.centre(grid.cell_of(at));
    const bool passes_clear = std::none_of(nearby_.begin(), nearby_.end(), [&](Vec2 other) {
      return distance_to_segment(other, start, p) < body;
    });
    if (distance(p, start) <= config_.yield_step_m && passes_clear &&
        segment_clear_leaving(grid, start, p, UnknownPolicy::Blocked)) {
      step = p;
      return true;
    }
    if (parent_[at] == at) break;
  }
  return true;
}

}  // namespace slam::planner

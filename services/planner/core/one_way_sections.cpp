// Pass 2 of the traffic rules (traffic_rules.hpp), one-way narrow stretches (`one_way_sections`,
// off by default). Where a robot's way runs through a passage in which no robot can stand clear of
// another's way (a door, a single-lane corridor), the stretch ahead, up to section_horizon_m, is its
// section once the entry is within lookahead_m.
// Invariant: no robot enters a section that a robot inside it, or a higher-ranked robot waiting to
// enter it, travels the other way; it waits `reach` before the mouth (reservations.cpp holds it
// there). Section waits alone form no cycle (each points at a robot inside or ranked above), and a
// robot inside keeps its section whatever its rank, so a section wait lasts at most while the
// robots ranked above it cross once each, provided the robots inside move.
#include <algorithm>
#include <limits>

#include "planner/core/traffic_geometry.hpp"
#include "planner/core/traffic_rules.hpp"

namespace slam::planner {

void TrafficRules::plan_sections(const PlanningGrid& grid, Robots robots) {
  const size_t n = robots.size();
  section_points_.clear();
  section_at_.resize(2 * n);
  entry_m_.resize(n);
  section_held_.resize(n, 0);
  for (size_t i = 0; i < n; ++i) build_section(grid, i, robots[i]);
  grant_sections(robots);
}

bool TrafficRules::narrow_at(const PlanningGrid& grid, Vec2 p, Vec2 along) const {
  const Vec2 side{-along.y, along.x};
  const double room = reach() + traffic::kYieldMarginM;
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

double TrafficRules::section_wait_m(size_t i) const {
  return std::max(0.0, entry_m_[i] - reach());
}

void TrafficRules::grant_sections(Robots robots) {
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

}  // namespace slam::planner

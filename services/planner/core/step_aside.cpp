// Stepping aside, the move passes 3 to 5 of the traffic rules (traffic_rules.hpp) send a robot on:
// a bounded breadth-first search over free cells for the nearest place off a given way, never
// squeezing past another robot, then the furthest point of the way there that is in sight and
// within one yield step.
#include <algorithm>
#include <limits>

#include "planner/core/line_of_sight.hpp"
#include "planner/core/traffic_geometry.hpp"
#include "planner/core/traffic_rules.hpp"

namespace slam::planner {
namespace {

using traffic::gap_to;
using traffic::kYieldMarginM;

}  // namespace

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

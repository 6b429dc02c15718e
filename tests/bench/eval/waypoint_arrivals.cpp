// Waypoints the planner counted reached (see waypoint_arrivals.hpp).
#include "eval/waypoint_arrivals.hpp"

#include <algorithm>

namespace slam::bench {

std::vector<Vec2> WaypointArrivals::update(const std::string& robot_id, const PathView& now,
                                           std::optional<Vec2> reported) {
  std::vector<Vec2> reached;
  const auto it = last_.find(robot_id);
  if (it != last_.end()) {
    const PathView& before = it->second;
    const size_t from = std::min<size_t>(before.current, before.waypoints.size());
    if (before.goal_id == now.goal_id && before.waypoints == now.waypoints) {
      const size_t to = std::min<size_t>(now.current, now.waypoints.size());
      for (size_t i = from; i < to; ++i) reached.push_back(before.waypoints[i]);
    } else if (from < before.waypoints.size() && reported) {
      // The path changed: reached only if the planner's rule consumes every remaining waypoint.
      size_t i = from;
      while (i < before.waypoints.size() && distance(*reported, before.waypoints[i]) <= tolerance_m_) ++i;
      if (i == before.waypoints.size())
        reached.assign(before.waypoints.begin() + static_cast<std::ptrdiff_t>(from), before.waypoints.end());
    }
  }
  last_[robot_id] = now;
  return reached;
}

}  // namespace slam::bench

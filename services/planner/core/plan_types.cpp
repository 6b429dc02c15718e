// Path measures behind plan_types.hpp.
#include "planner/core/plan_types.hpp"

#include <algorithm>

namespace slam::planner {

double path_length(const std::vector<Vec2>& path) {
  double total = 0.0;
  for (size_t i = 1; i < path.size(); ++i) total += distance(path[i - 1], path[i]);
  return total;
}

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  if (len2 <= 0.0) return distance(p, a);
  const double t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0);
  return distance(p, Vec2{a.x + t * dx, a.y + t * dy});
}

}  // namespace slam::planner

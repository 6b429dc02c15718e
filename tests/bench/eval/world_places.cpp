#include "eval/world_places.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace slam::bench {

std::vector<Vec2> reachable_places(const sim::World& world, Vec2 from, double clearance) {
  constexpr double kStep = 0.2;
  const sim::Bounds& b = world.bounds();
  const auto w = static_cast<int>((b.max.x - b.min.x) / kStep),
             h = static_cast<int>((b.max.y - b.min.y) / kStep);
  const auto at = [&](int x, int y) {
    return Vec2{b.min.x + (x + 0.5) * kStep, b.min.y + (y + 0.5) * kStep};
  };
  std::vector<uint8_t> seen(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
  std::vector<std::pair<int, int>> queue;
  int sx = std::clamp(static_cast<int>((from.x - b.min.x) / kStep), 0, w - 1);
  int sy = std::clamp(static_cast<int>((from.y - b.min.y) / kStep), 0, h - 1);
  queue.emplace_back(sx, sy);
  seen[static_cast<size_t>(sy * w + sx)] = 1;
  std::vector<Vec2> out;
  for (size_t head = 0; head < queue.size(); ++head) {
    const auto [x, y] = queue[head];
    const Vec2 p = at(x, y);
    if (world.is_free({p.x, p.y}, clearance)) out.push_back(p);
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h || seen[static_cast<size_t>(ny * w + nx)]) continue;
      const Vec2 q = at(nx, ny);
      // Moving between lattice points must stay clear of walls (no passing through a wall).
      if (!world.motion_clear({p.x, p.y}, {q.x, q.y}, 0.15)) continue;
      seen[static_cast<size_t>(ny * w + nx)] = 1;
      queue.emplace_back(nx, ny);
    }
  }
  return out;
}

Vec2 pick_place(std::span<const Vec2> places, Vec2 from, double min_trip_m, std::mt19937_64& rng) {
  std::uniform_int_distribution<size_t> pick(0, places.size() - 1);
  Vec2 place = places[pick(rng)];
  for (int attempt = 0; attempt < 20 && distance(place, from) < min_trip_m; ++attempt)
    place = places[pick(rng)];
  return place;
}

std::vector<Vec2> patrol_route(std::span<const Vec2> places, Vec2 from, size_t count, double min_trip_m,
                               std::mt19937_64& rng) {
  std::vector<Vec2> route;
  route.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    from = pick_place(places, from, min_trip_m, rng);
    route.push_back(from);
  }
  return route;
}

planner::PlanningGrid planning_grid_of(const sim::World& world, double resolution, double inflation) {
  const sim::Bounds& b = world.bounds();
  const GridGeometry geometry{b.min, resolution,
                              static_cast<int32_t>(std::ceil((b.max.x - b.min.x) / resolution)),
                              static_cast<int32_t>(std::ceil((b.max.y - b.min.y) / resolution))};
  std::vector<uint8_t> cells(geometry.cells(), kCellFree);
  const double half_diagonal = resolution * std::sqrt(0.5);
  for (size_t i = 0; i < cells.size(); ++i) {
    const Vec2 c = geometry.centre(geometry.cell_of(i));
    if (!world.is_free(c, half_diagonal)) {
      cells[i] = kCellOccupied;
    } else if (!world.is_free(c, inflation + 0.5 * resolution)) {
      cells[i] = kCellFree | kCellInflated;
    }
  }
  planner::PlanningGrid grid;
  if (!grid.reset(geometry, 1, 0, std::move(cells))) return {};
  return grid;
}

}  // namespace slam::bench

// Wall and coverage scores of an exported map (see map_metrics.hpp).
#include "eval/map_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slam::bench {
namespace {

constexpr double kNearWallCells = 1.5;
constexpr double kFoundWithinCells = 1.0;

Status check_axis_aligned(const MapImage& map) {
  if (map.origin_yaw != 0.0) return Error{"the map is rotated (origin yaw != 0): not supported"};
  if (!(map.resolution > 0.0) || map.cells.size() != static_cast<size_t>(map.width) * map.height)
    return Error{"the map's size, resolution and cells disagree"};
  return Status::ok();
}

GridGeometry geometry_of(const MapImage& map) {
  return {{map.origin_x, map.origin_y},
          map.resolution,
          static_cast<int32_t>(map.width),
          static_cast<int32_t>(map.height)};
}

double nearest_wall(Vec2 p, std::span<const sim::Segment> walls) {
  double best = std::numeric_limits<double>::infinity();
  for (const sim::Segment& w : walls) best = std::min(best, sim::distance_sq(p, w));
  return std::sqrt(best);
}

bool inside(Vec2 p, Vec2 lo, Vec2 hi) {
  return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
}

}  // namespace

bool segment_touches_box(const sim::Segment& s, Vec2 lo, Vec2 hi) {
  if (inside(s.a, lo, hi) || inside(s.b, lo, hi)) return true;
  const Vec2 c[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  for (int i = 0; i < 4; ++i)
    if (sim::segments_intersect(s, {c[i], c[(i + 1) % 4]})) return true;
  return false;
}

Result<WallScores> score_walls(const MapImage& map, std::span<const sim::Segment> walls) {
  SLAM_TRY(check_axis_aligned(map));
  const GridGeometry g = geometry_of(map);
  WallScores s;
  size_t near = 0;
  double distance_sum = 0.0;
  for (size_t i = 0; i < map.cells.size(); ++i) {
    if (map.cells[i] != kMapOccupied) continue;
    const double d = nearest_wall(g.centre(g.cell_of(i)), walls);
    ++s.occupied_cells;
    distance_sum += d;
    if (d <= kNearWallCells * g.resolution) ++near;
  }
  if (s.occupied_cells > 0) {
    s.near_wall_share = static_cast<double>(near) / static_cast<double>(s.occupied_cells);
    s.mean_wall_distance_m = distance_sum / static_cast<double>(s.occupied_cells);
  }

  // Walk every wall in steps of a quarter cell; a step counts as found when an occupied cell's
  // centre lies within one cell of it (only the 3 x 3 cells around it can).
  const double step = 0.25 * g.resolution;
  const double reach = kFoundWithinCells * g.resolution;
  double total = 0.0, found = 0.0;
  for (const sim::Segment& w : walls) {
    const double length = distance(w.a, w.b);
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    const double piece = length / n;
    for (int k = 0; k < n; ++k) {
      const Vec2 p = w.a + (w.b - w.a) * ((k + 0.5) / n);
      const Vec2 gp = g.to_grid(p);
      const auto cx = static_cast<int32_t>(std::floor(gp.x)), cy = static_cast<int32_t>(std::floor(gp.y));
      bool hit = false;
      for (int32_t dy = -1; dy <= 1 && !hit; ++dy) {
        for (int32_t dx = -1; dx <= 1 && !hit; ++dx) {
          const Cell c{cx + dx, cy + dy};
          hit = g.contains(c) && map.cells[g.index(c)] == kMapOccupied && distance(g.centre(c), p) <= reach;
        }
      }
      total += piece;
      if (hit) found += piece;
    }
  }
  s.wall_found_share = total > 0.0 ? found / total : 0.0;
  return s;
}

Result<CoverageScore> reachable_coverage(const MapImage& map, std::span<const sim::Segment> walls,
                                         std::span<const Vec2> starts) {
  SLAM_TRY(check_axis_aligned(map));
  if (walls.empty()) return Error{"no walls: the reachable space is unbounded"};
  const GridGeometry mg = geometry_of(map);
  const double res = map.resolution;
  // The truth lattice: the map's cell edges, extended over the walls' bounding box plus a cell.
  Vec2 lo = walls.front().a, hi = walls.front().a;
  for (const sim::Segment& w : walls) {
    for (const Vec2 p : {w.a, w.b}) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
  }
  const auto x0 = static_cast<int32_t>(std::floor((lo.x - map.origin_x) / res)) - 1;
  const auto y0 = static_cast<int32_t>(std::floor((lo.y - map.origin_y) / res)) - 1;
  const auto x1 = static_cast<int32_t>(std::ceil((hi.x - map.origin_x) / res)) + 1;
  const auto y1 = static_cast<int32_t>(std::ceil((hi.y - map.origin_y) / res)) + 1;
  const GridGeometry tg{{map.origin_x + x0 * res, map.origin_y + y0 * res}, res, x1 - x0, y1 - y0};

  std::vector<uint8_t> blocked(tg.cells(), 0);
  for (const sim::Segment& w : walls) {
    const Cell a = tg.clamped_cell_at({std::min(w.a.x, w.b.x), std::min(w.a.y, w.b.y)});
    const Cell b = tg.clamped_cell_at({std::max(w.a.x, w.b.x), std::max(w.a.y, w.b.y)});
    for (int32_t y = std::max(a.y - 1, 0); y <= std::min(b.y + 1, tg.height - 1); ++y) {
      for (int32_t x = std::max(a.x - 1, 0); x <= std::min(b.x + 1, tg.width - 1); ++x) {
        const Vec2 c0 = tg.corner({x, y});
        if (segment_touches_box(w, c0, c0 + Vec2{res, res})) blocked[tg.index({x, y})] = 1;
      }
    }
  }

  std::vector<uint8_t> reached(tg.cells(), 0);
  std::vector<Cell> queue;
  for (const Vec2& s : starts) {
    const auto c = tg.cell_at(s);
    if (!c || blocked[tg.index(*c)] || reached[tg.index(*c)]) continue;
    reached[tg.index(*c)] = 1;
    queue.push_back(*c);
  }
  // A cell any wall touches is blocked, so two open 4-neighbours never have a wall between them.
  constexpr int kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (size_t head = 0; head < queue.size(); ++head) {
    for (const auto& d : kSteps) {
      const Cell n{queue[head].x + d[0], queue[head].y + d[1]};
      if (!tg.contains(n) || blocked[tg.index(n)] || reached[tg.index(n)]) continue;
      reached[tg.index(n)] = 1;
      queue.push_back(n);
    }
  }

  CoverageScore score;
  score.reachable_cells = queue.size();
  for (const Cell& c : queue) {
    const Cell m{c.x + x0, c.y + y0};
    if (mg.contains(m) && map.cells[mg.index(m)] == kMapFree) ++score.known_free;
  }
  return score;
}

}  // namespace slam::bench

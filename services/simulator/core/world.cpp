// World validation and the wall index: each wall is registered in every grid cell it touches
// (exact conservative rasterisation, row by row), so cell-local queries never miss a wall.
#include "simulator/core/world.hpp"

#include <fmt/format.h>

#include <cmath>

namespace slam::sim {
namespace {

constexpr double kMinCell = 0.5;  // metres: a 4 m beam crosses about 8-16 cells
constexpr int kMaxCells = 256;    // per axis: bounds index memory for huge worlds

bool finite(Vec2 p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

}  // namespace

bool OccupancyImage::occupied_at(Vec2 p) const {
  const double fx = std::floor((p.x - origin.x) / resolution);
  const double fy = std::floor((p.y - origin.y) / resolution);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < width && fy < height)) return false;
  const auto i = static_cast<size_t>(fy) * static_cast<size_t>(width) + static_cast<size_t>(fx);
  return i < occupied.size() && occupied[i] != 0;
}

Result<World> World::create(std::string name, Bounds bounds, std::vector<Segment> walls,
                            OccupancyImage solid) {
  if (!finite(bounds.min) || !finite(bounds.max))
    return Error{fmt::format("world '{}': bounds are not finite", name)};
  if (!(bounds.width() > 0.0) || !(bounds.height() > 0.0))
    return Error{
        fmt::format("world '{}': size {} x {} m must be positive", name, bounds.width(), bounds.height())};
  if (bounds.width() > kMaxExtent || bounds.height() > kMaxExtent)
    return Error{fmt::format("world '{}': size {} x {} m exceeds the {} m limit", name, bounds.width(),
                             bounds.height(), kMaxExtent)};
  const double tol = 1e-9 * std::max(bounds.width(), bounds.height());
  const Bounds loose{{bounds.min.x - tol, bounds.min.y - tol}, {bounds.max.x + tol, bounds.max.y + tol}};
  for (size_t i = 0; i < walls.size(); ++i) {
    const Segment& s = walls[i];
    if (!finite(s.a) || !finite(s.b))
      return Error{fmt::format("world '{}': wall {} has a non-finite coordinate", name, i + 1)};
    if (!loose.contains(s.a) || !loose.contains(s.b))
      return Error{fmt::format("world '{}': wall {} ({},{})-({},{}) lies outside the bounds ({},{})-({},{})",
                               name, i + 1, s.a.x, s.a.y, s.b.x, s.b.y, bounds.min.x, bounds.min.y,
                               bounds.max.x, bounds.max.y)};
  }
  World w;
  w.name_ = std::move(name);
  w.bounds_ = bounds;
  w.solid_ = std::move(solid);
  const Vec2 lo = bounds.min, hi = bounds.max;
  w.walls_ = {{lo, {hi.x, lo.y}}, {{hi.x, lo.y}, hi}, {hi, {lo.x, hi.y}}, {{lo.x, hi.y}, lo}};
  w.walls_.insert(w.walls_.end(), walls.begin(), walls.end());
  w.build_index();
  return w;
}

void World::build_index() {
  grid_ = covering_grid(bounds_, kMinCell, kMaxCells);
  index_.reset(grid_.cells());
  for (size_t i = 0; i < walls_.size(); ++i) {
    const auto id = static_cast<uint32_t>(i);
    const Segment& s = walls_[i];
    const int y0 = grid_.clamped_cell_at({s.a.x, std::min(s.a.y, s.b.y)}).y;
    const int y1 = grid_.clamped_cell_at({s.a.x, std::max(s.a.y, s.b.y)}).y;
    const double dy = s.b.y - s.a.y;
    for (int cy = y0; cy <= y1; ++cy) {
      // The part of the segment inside this row of cells spans [xa, xb] in x.
      double xa = std::min(s.a.x, s.b.x), xb = std::max(s.a.x, s.b.x);
      if (dy != 0.0 && y0 != y1) {
        const double band_lo = grid_.origin.y + cy * grid_.resolution;
        const double band_hi = band_lo + grid_.resolution;
        const double ta = std::clamp((band_lo - s.a.y) / dy, 0.0, 1.0);
        const double tb = std::clamp((band_hi - s.a.y) / dy, 0.0, 1.0);
        const double xta = s.a.x + (s.b.x - s.a.x) * ta, xtb = s.a.x + (s.b.x - s.a.x) * tb;
        xa = std::min(xta, xtb);
        xb = std::max(xta, xtb);
      }
      const double eps = 1e-9 * grid_.resolution;
      const int x0 = grid_.clamped_cell_at({xa - eps, s.a.y}).x,
                x1 = grid_.clamped_cell_at({xb + eps, s.a.y}).x;
      for (int cx = x0; cx <= x1; ++cx) index_.add(bucket_index(grid_, {cx, cy}), id);
    }
  }
  index_.finish();
}

double World::cast(Vec2 origin, Vec2 dir, double max_range) const {
  double best = max_range;
  traverse_ray(grid_, origin, dir, max_range, [&](uint32_t cell, double t_exit) {
    for (uint32_t id : index_.at(cell)) best = std::min(best, ray_segment(origin, dir, walls_[id]));
    return best <= t_exit;
  });
  return best;
}

bool World::is_free(Vec2 p, double radius) const {
  if (!bounds_.contains(p) || solid_.occupied_at(p)) return false;
  const double r_sq = radius * radius;
  bool free = true;
  for_each_cell_in_box(grid_, {p.x - radius, p.y - radius}, {p.x + radius, p.y + radius}, [&](uint32_t cell) {
    for (uint32_t id : index_.at(cell))
      if (distance_sq(p, walls_[id]) < r_sq) free = false;
  });
  return free;
}

bool World::motion_clear(Vec2 from, Vec2 to, double radius) const {
  if (!is_free(to, radius)) return false;
  const Segment path{from, to};
  bool clear = true;
  const Vec2 lo{std::min(from.x, to.x), std::min(from.y, to.y)};
  const Vec2 hi{std::max(from.x, to.x), std::max(from.y, to.y)};
  for_each_cell_in_box(grid_, lo, hi, [&](uint32_t cell) {
    for (uint32_t id : index_.at(cell))
      if (segments_intersect(path, walls_[id])) clear = false;
  });
  return clear;
}

}  // namespace slam::sim

#pragma once
// Uniform bucket grid shared by the wall index and the per-tick robot index: a common GridGeometry
// sized to the world, flat per-cell item lists (rebuilt in bulk, capacity kept so a rebuild does not
// allocate), and a cell-by-cell ray walk so a beam only tests the items of the cells it crosses, nearest
// first.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "simulator/core/geometry.hpp"

namespace slam::sim {

// Cells of at least `min_cell` metres, at most `max_cells` per axis, covering `b`.
inline GridGeometry covering_grid(const Bounds& b, double min_cell, int max_cells) {
  GridGeometry g;
  g.origin = b.min;
  const double extent = std::max(b.width(), b.height());
  g.resolution = std::max(min_cell, extent / max_cells);
  g.width = std::clamp(static_cast<int>(std::ceil(b.width() / g.resolution)), 1, max_cells);
  g.height = std::clamp(static_cast<int>(std::ceil(b.height() / g.resolution)), 1, max_cells);
  return g;
}

inline uint32_t bucket_index(const GridGeometry& g, Cell c) {
  return static_cast<uint32_t>(g.index(c));
}

// Calls visit(index) for every cell overlapping the box [lo, hi] (clamped to the grid).
template <class Visit>
void for_each_cell_in_box(const GridGeometry& g, Vec2 lo, Vec2 hi, Visit&& visit) {
  const Cell c0 = g.clamped_cell_at(lo), c1 = g.clamped_cell_at(hi);
  for (int cy = c0.y; cy <= c1.y; ++cy)
    for (int cx = c0.x; cx <= c1.x; ++cx) visit(bucket_index(g, {cx, cy}));
}

// Walks the cells the ray (o, unit dir) crosses for t in [0, max_t], in order. visit(index,
// t_exit) gets the ray parameter where the ray leaves that cell and returns true to stop.
template <class Visit>
void traverse_ray(const GridGeometry& g, Vec2 o, Vec2 dir, double max_t, Visit&& visit) {
  // Clip to the grid box first so rays starting outside still walk the right cells.
  const double cell = g.resolution;
  const Vec2 top_right = g.corner({g.width, g.height});
  double t0 = 0.0, t1 = max_t;
  const double lo[2] = {g.origin.x, g.origin.y};
  const double hi[2] = {top_right.x, top_right.y};
  const double p[2] = {o.x, o.y};
  const double d[2] = {dir.x, dir.y};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0.0) {
      if (p[a] < lo[a] || p[a] > hi[a]) return;
      continue;
    }
    double ta = (lo[a] - p[a]) / d[a], tb = (hi[a] - p[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return;
  const Cell start = g.clamped_cell_at(o + dir * t0);
  int cx = start.x, cy = start.y;
  const int sx = dir.x > 0 ? 1 : -1, sy = dir.y > 0 ? 1 : -1;
  const double dtx = dir.x != 0.0 ? cell / std::abs(dir.x) : INFINITY;
  const double dty = dir.y != 0.0 ? cell / std::abs(dir.y) : INFINITY;
  double tx = dir.x != 0.0 ? (g.origin.x + (cx + (sx > 0 ? 1 : 0)) * cell - o.x) / dir.x : INFINITY;
  double ty = dir.y != 0.0 ? (g.origin.y + (cy + (sy > 0 ? 1 : 0)) * cell - o.y) / dir.y : INFINITY;
  while (true) {
    const double t_exit = std::min({tx, ty, t1});
    if (visit(bucket_index(g, {cx, cy}), t_exit) || t_exit >= t1) return;
    if (tx <= ty) {
      cx += sx;
      tx += dtx;
      if (cx < 0 || cx >= g.width) return;
    } else {
      cy += sy;
      ty += dty;
      if (cy < 0 || cy >= g.height) return;
    }
  }
}

// Items (uint32 ids) per cell in one flat array: stage (cell, item) pairs, then finish().
class Buckets {
 public:
  void reset(size_t cells) {
    cells_ = cells;
    staged_.clear();
  }
  void add(uint32_t cell, uint32_t item) { staged_.emplace_back(cell, item); }

  // Counting sort of the staged pairs into per-cell ranges.
  void finish() {
    start_.assign(cells_ + 1, 0);
    for (const auto& [cell, item] : staged_) ++start_[cell + 1];
    for (size_t c = 0; c < cells_; ++c) start_[c + 1] += start_[c];
    items_.resize(staged_.size());
    fill_.assign(start_.begin(), start_.end() - 1);
    for (const auto& [cell, item] : staged_) items_[fill_[cell]++] = item;
  }

  std::span<const uint32_t> at(uint32_t cell) const {
    return {items_.data() + start_[cell], items_.data() + start_[cell + 1]};
  }

 private:
  size_t cells_ = 0;
  std::vector<std::pair<uint32_t, uint32_t>> staged_;
  std::vector<uint32_t> start_;
  std::vector<uint32_t> fill_;
  std::vector<uint32_t> items_;
};

}  // namespace slam::sim

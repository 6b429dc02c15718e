// TileCanvas: the grid's drawing rules on a few tiles (see tile_canvas.hpp). The rules mirror
// OccupancyGrid::integrate (occupancy_grid.cpp); the partial re-render's tests compare both cell for cell.
#include "mapper/core/tile_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "mapper/core/ray_trace.hpp"

namespace slam::mapper {

void TileCanvas::reset(const GridGeometry& geometry, const GridConfig& config,
                       std::span<const uint32_t> tiles) {
  geometry_ = geometry;
  layout_ = TileLayout{geometry.width, geometry.height, kSide};
  tiles_x_ = layout_.tiles_x();
  log_odds_ = config.log_odds;
  max_range_m_ = config.max_range_m;
  legacy_ = config.legacy_mode;
  tiles_.assign(tiles.begin(), tiles.end());
  slot_of_tile_.assign(layout_.count(), -1);
  cells_.assign(tiles_.size() * static_cast<size_t>(kSide * kSide), CanvasCell{});
  bounds_ = CellBox{};
  for (size_t slot = 0; slot < tiles_.size(); ++slot) {
    slot_of_tile_[tiles_[slot]] = static_cast<int32_t>(slot);
    bounds_.unite(layout_.box(tiles_[slot]));
  }
  epoch_ = 0;
}

void TileCanvas::apply_prior(const MapImage& image) {
  // The checks and the per-cell sampling of OccupancyGrid::apply_prior (grid_edits.cpp).
  if (image.width == 0 || image.height == 0 || image.cells.size() != size_t{image.width} * image.height)
    return;
  if (!std::isfinite(image.resolution) || image.resolution <= 0.0) return;
  if (!std::isfinite(image.origin_x) || !std::isfinite(image.origin_y) || !std::isfinite(image.origin_yaw))
    return;
  const double c = std::cos(image.origin_yaw);
  const double s = std::sin(image.origin_yaw);
  const double res = geometry_.resolution;
  for (size_t slot = 0; slot < tiles_.size(); ++slot) {
    const CellBox b = layout_.box(tiles_[slot]);
    for (int32_t gy = b.y0; gy < b.y0 + b.height; ++gy) {
      const double wy = geometry_.origin.y + (gy + 0.5) * res - image.origin_y;
      for (int32_t gx = b.x0; gx < b.x0 + b.width; ++gx) {
        const double wx = geometry_.origin.x + (gx + 0.5) * res - image.origin_x;
        const double u = std::floor((c * wx + s * wy) / image.resolution);
        const double v = std::floor((-s * wx + c * wy) / image.resolution);
        if (u < 0 || v < 0 || u >= image.width || v >= image.height) continue;
        const uint8_t cell = image.cells[static_cast<size_t>(v) * image.width + static_cast<size_t>(u)];
        if (cell == kMapUnknown) continue;
        cells_[cell_index(slot, gx, gy)].log_odds =
            cell == kMapOccupied ? log_odds_.prior_occupied : log_odds_.prior_free;
      }
    }
  }
}

void TileCanvas::apply_baseline(const Baseline& baseline) {
  baseline.for_each_known([&](Vec2 centre, int16_t value) {
    const auto cell = geometry_.cell_at(centre);
    if (!cell) return;
    if (CanvasCell* c = at(cell->x, cell->y)) c->log_odds = value;
  });
}

MapBox TileCanvas::box() const {
  MapBox box;
  if (bounds_.empty()) return box;
  const double res = geometry_.resolution;
  box.add(Vec2{geometry_.origin.x + bounds_.x0 * res, geometry_.origin.y + bounds_.y0 * res});
  box.add(Vec2{geometry_.origin.x + (bounds_.x0 + bounds_.width) * res,
               geometry_.origin.y + (bounds_.y0 + bounds_.height) * res});
  return box;
}

bool TileCanvas::touches(const MapBox& box) const {
  if (box.empty() || bounds_.empty()) return false;
  const Vec2 lo = geometry_.to_grid({box.x0, box.y0});
  const Vec2 hi = geometry_.to_grid({box.x1, box.y1});
  // Cells of the box, clipped to the tiles' bounds (a cell of margin against rounding).
  const double bx0 = std::max<double>(std::floor(lo.x) - 1, bounds_.x0);
  const double by0 = std::max<double>(std::floor(lo.y) - 1, bounds_.y0);
  const double bx1 = std::min<double>(std::floor(hi.x) + 1, bounds_.x0 + bounds_.width - 1);
  const double by1 = std::min<double>(std::floor(hi.y) + 1, bounds_.y0 + bounds_.height - 1);
  if (!(bx0 <= bx1 && by0 <= by1)) return false;
  const auto tx0 = static_cast<int32_t>(bx0) / kSide, tx1 = static_cast<int32_t>(bx1) / kSide;
  const auto ty0 = static_cast<int32_t>(by0) / kSide, ty1 = static_cast<int32_t>(by1) / kSide;
  for (int32_t ty = ty0; ty <= ty1; ++ty)
    for (int32_t tx = tx0; tx <= tx1; ++tx)
      if (slot_of_tile_[static_cast<size_t>(ty) * static_cast<size_t>(layout_.tiles_x()) +
                        static_cast<size_t>(tx)] >= 0)
        return true;
  return false;
}

TileCanvas::Drawn TileCanvas::integrate(const ObservationView& obs) {
  // What OccupancyGrid::integrate refuses, refused alike.
  if (!std::isfinite(obs.x) || !std::isfinite(obs.y) || !std::isfinite(obs.theta)) return Drawn::Rejected;
  const double range2 = max_range_m_ * max_range_m_;
  const auto valid = [&](std::span<const Vec2> pts) {
    for (const Vec2& p : pts) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
      const double dx = p.x - obs.x, dy = p.y - obs.y;
      if (dx * dx + dy * dy > range2) return false;
    }
    return true;
  };
  if (!valid(obs.hits) || !valid(obs.misses)) return Drawn::Rejected;
  // Where the grid would grow, the drawing depends on how it grows: not for a canvas to decide.
  const auto inside = [&](Vec2 p) {
    const Vec2 g = geometry_.to_grid(p);
    const double fx = std::floor(g.x), fy = std::floor(g.y);
    return fx >= 0.0 && fy >= 0.0 && fx < geometry_.width && fy < geometry_.height;
  };
  if (!inside({obs.x, obs.y})) return Drawn::OutsideGrid;
  for (const Vec2& p : obs.hits)
    if (!inside(p)) return Drawn::OutsideGrid;
  for (const Vec2& p : obs.misses)
    if (!inside(p)) return Drawn::OutsideGrid;

  if (legacy_) {
    for (const Vec2& p : obs.hits) {
      const Cell c = *geometry_.cell_at(p);
      if (CanvasCell* cell = at(c.x, c.y)) cell->log_odds = log_odds_.clamp_max;
    }
    return Drawn::Yes;
  }
  draw_rays(obs);
  return Drawn::Yes;
}

void TileCanvas::draw_rays(const ObservationView& obs) {
  if (++epoch_ == 0) {  // stamp wrapped: old stamps could collide with new ones
    for (CanvasCell& c : cells_) c.mark = 0;
    epoch_ = 1;
  }
  const uint16_t epoch = epoch_;
  const int32_t hit = log_odds_.hit;
  const int32_t miss = log_odds_.miss;
  const int32_t hi = log_odds_.clamp_max;
  const int32_t lo = log_odds_.clamp_min;

  // Hits first, so no ray of the same observation clears a cell another beam saw occupied.
  for (const Vec2& p : obs.hits) {
    const Cell c = *geometry_.cell_at(p);
    CanvasCell* cell = at(c.x, c.y);
    if (!cell || cell->mark == epoch) continue;
    cell->mark = epoch;
    cell->log_odds = static_cast<int16_t>(std::min(cell->log_odds + hit, hi));
  }

  const auto cell_of = [&](Vec2 p) {
    const Vec2 g = geometry_.to_grid(p);
    return Cell{static_cast<int32_t>(std::floor(g.x)), static_cast<int32_t>(std::floor(g.y))};
  };
  const Cell robot = cell_of({obs.x, obs.y});
  const int32_t bx0 = bounds_.x0, by0 = bounds_.y0;
  const int32_t bx1 = bounds_.x0 + bounds_.width, by1 = bounds_.y0 + bounds_.height;
  // The cells trace_ray visits (start included, end not), those within the tiles only.
  const auto trace = [&](std::span<const Vec2> pts) {
    for (const Vec2& p : pts) {
      const Cell end = cell_of(p);
      if (std::max(robot.x, end.x) < bx0 || std::min(robot.x, end.x) >= bx1 ||
          std::max(robot.y, end.y) < by0 || std::min(robot.y, end.y) >= by1)
        continue;  // the ray's box misses every tile
      trace_ray_in_box(robot.x, robot.y, end.x, end.y, bx0, by0, bx1, by1, false, [&](int32_t x, int32_t y) {
        CanvasCell* cell = at(x, y);
        if (!cell) return;
        const int32_t old = cell->log_odds;
        if (old != lo && cell->mark != epoch) {
          cell->mark = epoch;
          cell->log_odds = static_cast<int16_t>(std::max(old + miss, lo));
        }
      });
    }
  };
  trace(obs.hits);
  trace(obs.misses);
}

size_t TileCanvas::memory_bytes() const {
  return tiles_.capacity() * sizeof(uint32_t) + slot_of_tile_.capacity() * sizeof(int32_t) +
         cells_.capacity() * sizeof(CanvasCell);
}

}  // namespace slam::mapper

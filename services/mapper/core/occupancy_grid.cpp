// Grid construction, observation integration (validation, growth, ray casting) and cell updates.
// Edits, priors, export and dirty tracking live in grid_edits.cpp.
#include "mapper/core/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mapper/core/ray_trace.hpp"

namespace slam::mapper {
namespace {

std::string point_text(const char* kind, size_t i, double x, double y) {
  return std::string(kind) + " " + std::to_string(i) + " at (" + std::to_string(x) + ", " +
         std::to_string(y) + ")";
}

}  // namespace

OccupancyGrid::OccupancyGrid(const GridConfig& config)
    : config_(config),
      occ_(config.log_odds.occupied_threshold),
      free_(config.log_odds.free_threshold),
      max_side_(static_cast<int32_t>(cells_for(config.max_extent_m, config.resolution))),
      grow_chunk_(cells_for(config.grow_chunk_m, config.resolution)),
      width_(static_cast<int32_t>(cells_for(config.width_m, config.resolution))),
      height_(static_cast<int32_t>(cells_for(config.height_m, config.resolution))) {
  const size_t n = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  cells_.assign(n, CellEvidence{});
  classes_.assign(n, kCellUnknown);
  inflation_.configure(config.inflation_radius, config.resolution);
  inflation_.reset(width_, height_);
  dirty_.reset({width_, height_, kGridTileSide});
}

Result<OccupancyGrid> OccupancyGrid::create(const GridConfig& config) {
  if (Status s = validate(config); !s) return s.error();
  return OccupancyGrid(config);
}

double OccupancyGrid::cell_x(double x) const {
  return std::floor((x - origin_x()) / config_.resolution);
}
double OccupancyGrid::cell_y(double y) const {
  return std::floor((y - origin_y()) / config_.resolution);
}

void OccupancyGrid::mark_dirty(size_t i) {
  dirty_.mark(static_cast<int32_t>(i % static_cast<size_t>(width_)),
              static_cast<int32_t>(i / static_cast<size_t>(width_)));
}

// Every class change goes through here: it keeps the inflation layer and the dirty tiles in step.
void OccupancyGrid::set_class(size_t i, uint8_t cls) {
  const uint8_t old = classes_[i];
  if (old == cls) return;
  classes_[i] = cls;
  mark_dirty(i);
  const bool was = is_wall(old);
  const bool now = is_wall(cls);
  if (was == now) return;
  const auto x = static_cast<int32_t>(i % static_cast<size_t>(width_));
  const auto y = static_cast<int32_t>(i / static_cast<size_t>(width_));
  if (now) {
    inflation_.add(x, y, [this](size_t j) {
      classes_[j] = static_cast<uint8_t>(classes_[j] | kCellInflated);
      mark_dirty(j);
    });
  } else {
    inflation_.remove(x, y, [this](size_t j) {
      classes_[j] = static_cast<uint8_t>(classes_[j] & ~kCellInflated);
      mark_dirty(j);
    });
  }
}

void OccupancyGrid::set_value(size_t i, int32_t value) {
  const int32_t old = cells_[i].log_odds;
  if (old == value) return;
  cells_[i].log_odds = static_cast<int16_t>(value);
  const uint8_t state = state_of(value);
  if (state != state_of(old)) set_class(i, static_cast<uint8_t>((classes_[i] & ~kCellStateMask) | state));
}

bool OccupancyGrid::fits(int64_t bx0, int64_t by0, int64_t bx1, int64_t by1) const {
  return std::max<int64_t>(bx1, width_) - std::min<int64_t>(bx0, 0) <= max_side_ &&
         std::max<int64_t>(by1, height_) - std::min<int64_t>(by0, 0) <= max_side_;
}

namespace {

// New [lo, hi) along one axis covering [need_lo, need_hi) and [0, size), padded by `chunk` on the
// sides that grow, trimmed back towards the need when padding would pass `max_side`.
void grow_axis(int64_t need_lo, int64_t need_hi, int64_t size, int64_t chunk, int64_t max_side, int64_t* lo,
               int64_t* hi) {
  const int64_t base_lo = std::min<int64_t>(need_lo, 0);
  const int64_t base_hi = std::max<int64_t>(need_hi, size);
  *lo = need_lo < 0 ? std::min(base_lo, -chunk) : 0;
  *hi = need_hi > size ? std::max(base_hi, size + chunk) : size;
  if (*hi - *lo > max_side) *hi = std::max(base_hi, *lo + max_side);
  if (*hi - *lo > max_side) *lo = std::min(base_lo, *hi - max_side);
}

}  // namespace

void OccupancyGrid::grow(int64_t bx0, int64_t by0, int64_t bx1, int64_t by1) {
  int64_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  grow_axis(bx0, bx1, width_, grow_chunk_, max_side_, &x0, &x1);
  grow_axis(by0, by1, height_, grow_chunk_, max_side_, &y0, &y1);
  resize(x0, y0, x1, y1);
}

void OccupancyGrid::resize(int64_t x0, int64_t y0, int64_t x1, int64_t y1) {
  const auto new_w = static_cast<int32_t>(x1 - x0);
  const auto new_h = static_cast<int32_t>(y1 - y0);
  const size_t n = static_cast<size_t>(new_w) * static_cast<size_t>(new_h);
  std::vector<CellEvidence> grown(n, CellEvidence{});
  std::vector<uint8_t> cls(n, kCellUnknown);
  const auto shift_x = static_cast<size_t>(-x0);
  const auto shift_y = static_cast<size_t>(-y0);
  for (int32_t y = 0; y < height_; ++y) {
    const size_t src = index(0, y);
    const size_t dst = (static_cast<size_t>(y) + shift_y) * static_cast<size_t>(new_w) + shift_x;
    for (int32_t x = 0; x < width_; ++x)  // stamps restart at 0 with epoch_ below
      grown[dst + static_cast<size_t>(x)].log_odds = cells_[src + static_cast<size_t>(x)].log_odds;
    for (int32_t x = 0; x < width_; ++x)  // inflation is recomputed below
      cls[dst + static_cast<size_t>(x)] =
          static_cast<uint8_t>(classes_[src + static_cast<size_t>(x)] & ~kCellInflated);
  }
  cells_ = std::move(grown);
  classes_ = std::move(cls);
  epoch_ = 0;
  width_ = new_w;
  height_ = new_h;
  offset_x_ += x0;
  offset_y_ += y0;
  ++layout_version_;
  // Growth is rare (chunked), so a full re-inflation is simpler than patching disks at the old border.
  inflation_.reset(width_, height_);
  for (size_t i = 0; i < n; ++i) {
    if (!is_wall(classes_[i])) continue;
    inflation_.add(static_cast<int32_t>(i % static_cast<size_t>(width_)),
                   static_cast<int32_t>(i / static_cast<size_t>(width_)),
                   [this](size_t j) { classes_[j] = static_cast<uint8_t>(classes_[j] | kCellInflated); });
  }
  dirty_.reset({width_, height_, kGridTileSide});
  dirty_.mark_all();
}

Result<IntegrateStats> OccupancyGrid::integrate(const ObservationView& obs) {
  if (!std::isfinite(obs.x) || !std::isfinite(obs.y) || !std::isfinite(obs.theta))
    return Error{"robot pose (" + std::to_string(obs.x) + ", " + std::to_string(obs.y) + ") is not finite"};
  const double range2 = config_.max_range_m * config_.max_range_m;
  const auto check = [&](std::span<const Vec2> pts, const char* kind) -> Status {
    for (size_t i = 0; i < pts.size(); ++i) {
      const Vec2& p = pts[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        return Error{point_text(kind, i, p.x, p.y) + " is not finite"};
      const double dx = p.x - obs.x;
      const double dy = p.y - obs.y;
      if (dx * dx + dy * dy > range2)
        return Error{point_text(kind, i, p.x, p.y) + " is " + std::to_string(std::sqrt(dx * dx + dy * dy)) +
                     " m from the robot, beyond max_range_m " + std::to_string(config_.max_range_m)};
    }
    return Status::ok();
  };
  if (Status s = check(obs.hits, "hit"); !s) return s.error();
  if (Status s = check(obs.misses, "miss"); !s) return s.error();

  // The robot must be reachable; each point extends the needed box only while it still fits.
  const double px = cell_x(obs.x);
  const double py = cell_y(obs.y);
  if (!(std::max<double>(px + 1, width_) - std::min(px, 0.0) <= max_side_ &&
        std::max<double>(py + 1, height_) - std::min(py, 0.0) <= max_side_))
    return Error{"robot pose (" + std::to_string(obs.x) + ", " + std::to_string(obs.y) +
                 ") lies beyond the maximum map extent of " + std::to_string(config_.max_extent_m) + " m"};
  int64_t bx0 = static_cast<int64_t>(px), bx1 = bx0 + 1;
  int64_t by0 = static_cast<int64_t>(py), by1 = by0 + 1;
  // A point past the limit pulls the grid only as far as the limit allows (its hit is clipped).
  const auto extend = [&](std::span<const Vec2> pts) {
    for (const Vec2& p : pts) {
      const int64_t ux0 = std::min<int64_t>(bx0, 0), ux1 = std::max<int64_t>(bx1, width_);
      const int64_t uy0 = std::min<int64_t>(by0, 0), uy1 = std::max<int64_t>(by1, height_);
      const auto cx = std::clamp(static_cast<int64_t>(cell_x(p.x)), ux1 - max_side_, ux0 + max_side_ - 1);
      const auto cy = std::clamp(static_cast<int64_t>(cell_y(p.y)), uy1 - max_side_, uy0 + max_side_ - 1);
      bx0 = std::min(bx0, cx), bx1 = std::max(bx1, cx + 1);
      by0 = std::min(by0, cy), by1 = std::max(by1, cy + 1);
    }
  };
  extend(obs.hits);
  extend(obs.misses);
  IntegrateStats stats;
  if (bx0 < 0 || by0 < 0 || bx1 > width_ || by1 > height_) {
    grow(bx0, by0, bx1, by1);
    stats.grew = true;
  }
  if (config_.legacy_mode) {
    integrate_legacy(obs, &stats);
  } else {
    integrate_rays(obs, &stats);
  }
  return stats;
}

void OccupancyGrid::integrate_legacy(const ObservationView& obs, IntegrateStats* stats) {
  const GridGeometry geometry = this->geometry();
  for (const Vec2& p : obs.hits) {
    const auto cell = geometry.cell_at(p);
    if (!cell) {
      ++stats->clipped;
      continue;
    }
    set_value(index(cell->x, cell->y), config_.log_odds.clamp_max);
    ++stats->hits;
  }
}

void OccupancyGrid::integrate_rays(const ObservationView& obs, IntegrateStats* stats) {
  if (++epoch_ == 0) {  // stamp wrapped: old stamps could collide with new ones
    for (CellEvidence& c : cells_) c.mark = 0;
    epoch_ = 1;
  }
  const uint16_t epoch = epoch_;
  const int32_t hit = config_.log_odds.hit;
  const int32_t miss = config_.log_odds.miss;
  const int32_t hi = config_.log_odds.clamp_max;
  const int32_t lo = config_.log_odds.clamp_min;

  // Hits first, so no ray of the same observation clears a cell another beam saw occupied.
  const GridGeometry geometry = this->geometry();
  for (const Vec2& p : obs.hits) {
    const auto cell = geometry.cell_at(p);
    if (!cell) continue;
    const size_t i = index(cell->x, cell->y);
    if (cells_[i].mark == epoch) continue;
    cells_[i].mark = epoch;
    set_value(i, std::min(cells_[i].log_odds + hit, hi));
    ++stats->hits;
  }

  const auto rx = static_cast<int32_t>(cell_x(obs.x));
  const auto ry = static_cast<int32_t>(cell_y(obs.y));
  const auto clear = [&](size_t i) {
    CellEvidence& cell = cells_[i];
    const int32_t old = cell.log_odds;
    // Saturated free space (most cells a ray crosses) needs neither an update nor a stamp: no hit of
    // this observation touched it (a hit lifts it above clamp_min) and a miss cannot lower it.
    if (old == lo || cell.mark == epoch) return;
    cell.mark = epoch;
    set_value(i, std::max(old + miss, lo));
  };
  const auto trace = [&](std::span<const Vec2> pts, bool is_hit) {
    for (const Vec2& p : pts) {
      const auto ex = static_cast<int32_t>(cell_x(p.x));
      const auto ey = static_cast<int32_t>(cell_y(p.y));
      const bool outside = ex < 0 || ey < 0 || ex >= width_ || ey >= height_;
      if (is_hit && outside) ++stats->clipped;
      if (!is_hit) ++stats->misses;
      stats->cells_traced += trace_ray(rx, ry, ex, ey, width_, height_, false, clear);
    }
  };
  trace(obs.hits, true);
  trace(obs.misses, false);
}

}  // namespace slam::mapper

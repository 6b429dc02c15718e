// The grid's operator-facing side: manual obstructions, map priors and trinary export; and the tiles a
// partial re-render drew.
#include <algorithm>
#include <cmath>
#include <string>

#include "mapper/core/occupancy_grid.hpp"
#include "mapper/core/store_baseline.hpp"
#include "mapper/core/tile_canvas.hpp"

namespace slam::mapper {

Status OccupancyGrid::obstruct(double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) return Error{"obstruction point is not finite"};
  const double fx = cell_x(x);
  const double fy = cell_y(y);
  const bool reachable = std::max<double>(fx + 1, width_) - std::min(fx, 0.0) <= max_side_ &&
                         std::max<double>(fy + 1, height_) - std::min(fy, 0.0) <= max_side_;
  if (!reachable)
    return Error{"obstruction (" + std::to_string(x) + ", " + std::to_string(y) +
                 ") lies beyond the maximum map extent of " + std::to_string(config_.max_extent_m) + " m"};
  const auto cx = static_cast<int64_t>(fx);
  const auto cy = static_cast<int64_t>(fy);
  if (cx < 0 || cy < 0 || cx >= width_ || cy >= height_) grow(cx, cy, cx + 1, cy + 1);
  const auto cell = cell_at({x, y});
  if (!cell) return Error{"obstruction point could not be placed in the grid"};
  const size_t i = index(cell->x, cell->y);
  if (classes_[i] & kCellObstructed) return Status::ok();
  obstructions_.push_back({x, y});
  set_class(i, static_cast<uint8_t>(classes_[i] | kCellObstructed));
  return Status::ok();
}

std::vector<Vec2> OccupancyGrid::unobstruct(double x, double y) {
  std::vector<Vec2> removed;
  const auto cell = cell_at({x, y});
  if (!cell) return removed;
  const auto same_cell = [&](const Vec2& p) { return cell_at(p) == cell; };
  for (const Vec2& p : obstructions_)
    if (same_cell(p)) removed.push_back(p);
  std::erase_if(obstructions_, same_cell);
  const size_t i = index(cell->x, cell->y);
  set_class(i, static_cast<uint8_t>(classes_[i] & ~kCellObstructed));
  return removed;
}

void OccupancyGrid::clear_obstructions() {
  for (const Vec2& p : obstructions_) {
    const auto cell = cell_at(p);
    if (!cell) continue;
    const size_t i = index(cell->x, cell->y);
    set_class(i, static_cast<uint8_t>(classes_[i] & ~kCellObstructed));
  }
  obstructions_.clear();
}

int64_t OccupancyGrid::apply_baseline(const Baseline& baseline) {
  const GridGeometry& b = baseline.geometry;
  if (!(b.resolution > 0.0) || b.width <= 0 || b.height <= 0) return 0;
  // The cells of its first and last cell centres, in this layout.
  const auto x0 = static_cast<int64_t>(cell_x(b.origin.x + 0.5 * b.resolution));
  const auto y0 = static_cast<int64_t>(cell_y(b.origin.y + 0.5 * b.resolution));
  const auto x1 = static_cast<int64_t>(cell_x(b.origin.x + (b.width - 0.5) * b.resolution)) + 1;
  const auto y1 = static_cast<int64_t>(cell_y(b.origin.y + (b.height - 0.5) * b.resolution)) + 1;
  if ((x0 < 0 || y0 < 0 || x1 > width_ || y1 > height_) && fits(x0, y0, x1, y1)) {
    if (b.resolution == config_.resolution)  // the layout the rebuild it replaces had: no padding
      resize(std::min<int64_t>(x0, 0), std::min<int64_t>(y0, 0), std::max<int64_t>(x1, width_),
             std::max<int64_t>(y1, height_));
    else
      grow(x0, y0, x1, y1);
  }
  const GridGeometry g = geometry();
  int64_t cells = 0;
  baseline.for_each_known([&](Vec2 centre, int16_t value) {
    const auto cell = g.cell_at(centre);
    if (!cell) return;
    set_value(index(cell->x, cell->y), value);
    ++cells;
  });
  return cells;
}

Result<int64_t> OccupancyGrid::apply_prior(const MapImage& image) {
  if (image.width == 0 || image.height == 0 || image.cells.size() != size_t{image.width} * image.height)
    return Error{"prior map: cell count does not match width*height"};
  if (!std::isfinite(image.resolution) || image.resolution <= 0.0)
    return Error{"prior map: resolution must be > 0"};
  if (!std::isfinite(image.origin_x) || !std::isfinite(image.origin_y) || !std::isfinite(image.origin_yaw))
    return Error{"prior map: origin is not finite"};
  const double c = std::cos(image.origin_yaw);
  const double s = std::sin(image.origin_yaw);
  const double w_m = image.width * image.resolution;
  const double h_m = image.height * image.resolution;
  // Bounding box of the (possibly rotated) image in cells of the current layout.
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  const auto image_box = [&] {
    min_x = min_y = HUGE_VAL;
    max_x = max_y = -HUGE_VAL;
    for (const auto& [u, v] : {std::pair{0.0, 0.0}, {w_m, 0.0}, {0.0, h_m}, {w_m, h_m}}) {
      const double wx = image.origin_x + c * u - s * v;
      const double wy = image.origin_y + s * u + c * v;
      min_x = std::min(min_x, cell_x(wx));
      max_x = std::max(max_x, cell_x(wx));
      min_y = std::min(min_y, cell_y(wy));
      max_y = std::max(max_y, cell_y(wy));
    }
  };
  image_box();
  // Clamp the wanted box to what the maximum extent allows (the rest of the image is dropped).
  const double lim = static_cast<double>(max_side_);
  int64_t bx0 = static_cast<int64_t>(std::max(min_x, width_ - lim));
  int64_t by0 = static_cast<int64_t>(std::max(min_y, height_ - lim));
  const auto bx1 = static_cast<int64_t>(std::min(max_x + 1, lim));
  const auto by1 = static_cast<int64_t>(std::min(max_y + 1, lim));
  if (bx1 <= bx0 || by1 <= by0) return Error{"prior map lies entirely beyond the maximum map extent"};
  if (!fits(bx0, by0, bx1, by1)) {
    bx0 = std::max<int64_t>(bx0, std::max<int64_t>(bx1, width_) - max_side_);
    by0 = std::max<int64_t>(by0, std::max<int64_t>(by1, height_) - max_side_);
  }
  if (bx0 < 0 || by0 < 0 || bx1 > width_ || by1 > height_) grow(bx0, by0, bx1, by1);
  image_box();
  const auto x0 = static_cast<int32_t>(std::clamp<double>(min_x, 0, width_));
  const auto x1 = static_cast<int32_t>(std::clamp<double>(max_x + 1, 0, width_));
  const auto y0 = static_cast<int32_t>(std::clamp<double>(min_y, 0, height_));
  const auto y1 = static_cast<int32_t>(std::clamp<double>(max_y + 1, 0, height_));

  int64_t set = 0;
  const double res = config_.resolution;
  for (int32_t gy = y0; gy < y1; ++gy) {
    const double wy = origin_y() + (gy + 0.5) * res - image.origin_y;
    for (int32_t gx = x0; gx < x1; ++gx) {
      const double wx = origin_x() + (gx + 0.5) * res - image.origin_x;
      const double u = std::floor((c * wx + s * wy) / image.resolution);
      const double v = std::floor((-s * wx + c * wy) / image.resolution);
      if (u < 0 || v < 0 || u >= image.width || v >= image.height) continue;
      const uint8_t cell = image.cells[static_cast<size_t>(v) * image.width + static_cast<size_t>(u)];
      if (cell == kMapUnknown) continue;
      set_value(index(gx, gy),
                cell == kMapOccupied ? config_.log_odds.prior_occupied : config_.log_odds.prior_free);
      ++set;
    }
  }
  return set;
}

void OccupancyGrid::redraw(const TileCanvas& canvas) {
  canvas.for_each_cell([this](int32_t x, int32_t y, int16_t log_odds) { set_value(index(x, y), log_odds); });
}

MapImage OccupancyGrid::to_map_image() const {
  MapImage map;
  map.width = static_cast<uint32_t>(width_);
  map.height = static_cast<uint32_t>(height_);
  map.resolution = config_.resolution;
  map.origin_x = origin_x();
  map.origin_y = origin_y();
  map.cells.resize(classes_.size());
  for (size_t i = 0; i < classes_.size(); ++i) {
    const uint8_t cls = classes_[i];
    map.cells[i] = (cls & kCellObstructed) ? kMapOccupied : static_cast<uint8_t>(cls & kCellStateMask);
  }
  return map;
}

}  // namespace slam::mapper

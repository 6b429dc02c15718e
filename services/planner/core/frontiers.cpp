// Frontier extraction and clustering. Flags live in a flat byte array beside the grid so a patch
// touches only its box, and clustering scans bytes rather than grid octets.
#include "planner/core/frontiers.hpp"

#include <algorithm>
#include <limits>

namespace slam::planner {

void FrontierMap::rebuild(const PlanningGrid& grid) {
  width_ = grid.geometry().width;
  height_ = grid.geometry().height;
  flags_.assign(grid.cells().size(), 0);
  count_ = 0;
  if (grid.empty()) return;
  recompute(grid, 0, 0, grid.width() - 1, grid.height() - 1);
}

void FrontierMap::update(const PlanningGrid& grid, const CellBox& box) {
  if (width_ != grid.geometry().width || height_ != grid.geometry().height ||
      flags_.size() != grid.cells().size()) {
    rebuild(grid);
    return;
  }
  if (box.empty()) return;
  const int32_t x0 = std::max(0, box.x0 - 1);
  const int32_t y0 = std::max(0, box.y0 - 1);
  const int32_t x1 = std::min(grid.width() - 1, box.x0 + box.width);
  const int32_t y1 = std::min(grid.height() - 1, box.y0 + box.height);
  if (x0 > x1 || y0 > y1) return;
  recompute(grid, x0, y0, x1, y1);
}

void FrontierMap::recompute(const PlanningGrid& grid, int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
  const uint8_t* cells = grid.cells().data();
  const int32_t w = grid.width();
  const int32_t h = grid.height();
  for (int32_t y = y0; y <= y1; ++y) {
    const size_t row = static_cast<size_t>(y) * static_cast<size_t>(w);
    const uint8_t* below = y > 0 ? cells + row - static_cast<size_t>(w) : nullptr;
    const uint8_t* above = y + 1 < h ? cells + row + static_cast<size_t>(w) : nullptr;
    for (int32_t x = x0; x <= x1; ++x) {
      const uint8_t c = cells[row + static_cast<size_t>(x)];
      bool frontier = false;
      if (cell_free(c) && !cell_blocked(c)) {
        frontier = (x > 0 && cell_unknown(cells[row + static_cast<size_t>(x) - 1])) ||
                   (x + 1 < w && cell_unknown(cells[row + static_cast<size_t>(x) + 1])) ||
                   (below != nullptr && cell_unknown(below[x])) ||
                   (above != nullptr && cell_unknown(above[x]));
      }
      uint8_t& flag = flags_[row + static_cast<size_t>(x)];
      const auto now = static_cast<uint8_t>(frontier);
      if (flag != now) {
        if (frontier) {
          ++count_;
        } else {
          --count_;
        }
        flag = now;
      }
    }
  }
}

void FrontierMap::cluster(const PlanningGrid& grid, uint32_t min_cells, std::vector<FrontierCluster>& out) {
  out.clear();
  if (count_ == 0 || flags_.size() != grid.cells().size()) return;
  if (visited_.size() != flags_.size()) {
    visited_.assign(flags_.size(), 0);
    visit_stamp_ = 0;
  }
  if (visit_stamp_ == std::numeric_limits<uint32_t>::max()) {
    std::fill(visited_.begin(), visited_.end(), 0);
    visit_stamp_ = 0;
  }
  const uint32_t stamp = ++visit_stamp_;
  const int32_t w = grid.width();
  const int32_t h = grid.height();
  const size_t n = flags_.size();
  for (size_t i = 0; i < n; ++i) {
    if (flags_[i] == 0 || visited_[i] == stamp) continue;
    queue_.clear();
    queue_.push_back(static_cast<uint32_t>(i));
    visited_[i] = stamp;
    double sx = 0.0;
    double sy = 0.0;
    for (size_t head = 0; head < queue_.size(); ++head) {
      const Cell c = grid.cell_of(queue_[head]);
      sx += c.x;
      sy += c.y;
      for (int32_t dy = -1; dy <= 1; ++dy) {
        for (int32_t dx = -1; dx <= 1; ++dx) {
          const int32_t nx = c.x + dx;
          const int32_t ny = c.y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const size_t ni = static_cast<size_t>(ny) * static_cast<size_t>(w) + static_cast<size_t>(nx);
          if (flags_[ni] == 0 || visited_[ni] == stamp) continue;
          visited_[ni] = stamp;
          queue_.push_back(static_cast<uint32_t>(ni));
        }
      }
    }
    if (queue_.size() < min_cells) continue;
    const double size = static_cast<double>(queue_.size());
    const Vec2 mean{sx / size, sy / size};  // in cell indices
    Cell best = grid.cell_of(queue_[0]);
    double best_d2 = std::numeric_limits<double>::infinity();
    for (uint32_t q : queue_) {
      const Cell c = grid.cell_of(q);
      const double d2 = (c.x - mean.x) * (c.x - mean.x) + (c.y - mean.y) * (c.y - mean.y);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = c;
      }
    }
    const double res = grid.resolution();
    const Vec2 origin = grid.geometry().origin;
    out.push_back(FrontierCluster{static_cast<uint32_t>(queue_.size()),
                                  Vec2{origin.x + (mean.x + 0.5) * res, origin.y + (mean.y + 0.5) * res},
                                  best});
  }
}

}  // namespace slam::planner

#pragma once
// Integer Bresenham traversal over a width x height cell array, clipped to it. Header-only so the
// per-cell visitor inlines: the mapper's hot loop is this function, and it must not allocate.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

namespace slam::mapper {

// Visits the cells trace_ray (below) would, as coordinates, skipping those outside the box
// [bx0, bx1) x [by0, by1): visit(x, y). A ray that leaves the box after crossing it stops there (the
// box is convex). Returns the number of cells visited.
template <class Visit>
int64_t trace_ray_in_box(int32_t x0, int32_t y0, int32_t x1, int32_t y1, int32_t bx0, int32_t by0,
                         int32_t bx1, int32_t by1, bool include_end, Visit&& visit) {
  const int64_t dx = std::llabs(int64_t{x1} - x0);
  const int64_t dy = -std::llabs(int64_t{y1} - y0);
  const int32_t sx = x0 < x1 ? 1 : -1;
  const int32_t sy = y0 < y1 ? 1 : -1;
  const int64_t steps = (dx > -dy ? dx : -dy) + (include_end ? 1 : 0);
  int64_t err = dx + dy;
  int64_t visited = 0;
  int32_t x = x0;
  int32_t y = y0;
  for (int64_t i = 0; i < steps; ++i) {
    if (x >= bx0 && y >= by0 && x < bx1 && y < by1) {
      visit(x, y);
      ++visited;
    } else if (visited > 0) {
      break;  // left the box after crossing it: nothing further can be inside
    }
    const int64_t e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y += sy;
    }
  }
  return visited;
}

// Visits the 8-connected Bresenham cells from (x0, y0) to (x1, y1), calling visit(linear_index)
// with linear_index = y * width + x. The start cell is visited; the end cell only when include_end.
// Cells outside [0, width) x [0, height) are skipped: a ray that leaves the grid stops there, one
// that starts outside is visited from where it enters. Returns the number of cells visited.
template <class Visit>
int64_t trace_ray(int32_t x0, int32_t y0, int32_t x1, int32_t y1, int32_t width, int32_t height,
                  bool include_end, Visit&& visit) {
  const int64_t dx = std::llabs(int64_t{x1} - x0);
  const int64_t dy = -std::llabs(int64_t{y1} - y0);
  const int32_t sx = x0 < x1 ? 1 : -1;
  const int32_t sy = y0 < y1 ? 1 : -1;
  const int64_t steps = (dx > -dy ? dx : -dy) + (include_end ? 1 : 0);
  int64_t err = dx + dy;
  const auto inside = [&](int32_t x, int32_t y) { return x >= 0 && y >= 0 && x < width && y < height; };

  if (inside(x0, y0) && inside(x1, y1)) {
    // Common case: both ends inside, so every cell between is too (the grid is convex).
    const ptrdiff_t step_y = static_cast<ptrdiff_t>(sy) * width;
    ptrdiff_t idx = static_cast<ptrdiff_t>(y0) * width + x0;
    for (int64_t i = 0; i < steps; ++i) {
      visit(static_cast<size_t>(idx));
      const int64_t e2 = 2 * err;
      if (e2 >= dy) {
        err += dy;
        idx += sx;
      }
      if (e2 <= dx) {
        err += dx;
        idx += step_y;
      }
    }
    return steps;
  }

  return trace_ray_in_box(x0, y0, x1, y1, 0, 0, width, height, include_end, [&](int32_t x, int32_t y) {
    visit(static_cast<size_t>(static_cast<ptrdiff_t>(y) * width + x));
  });
}

}  // namespace slam::mapper

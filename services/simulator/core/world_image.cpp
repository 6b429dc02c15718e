// Occupancy image to walls. A boundary between two cells is a wall when exactly one of them is
// occupied; consecutive boundary pieces on the same grid line merge into one segment, so the
// segment count grows with the outline's corners rather than with its area.
#include "simulator/core/world_image.hpp"

#include <fmt/format.h>

#include <cmath>

namespace slam::sim {
namespace {

constexpr int kMaxSide = 1 << 15;  // cells per side; bigger images are not maps of rooms

}  // namespace

Result<World> world_from_image(const OccupancyImage& image, std::string name) {
  const int w = image.width, h = image.height;
  if (w <= 0 || h <= 0 || w > kMaxSide || h > kMaxSide)
    return Error{fmt::format("map '{}': image size {}x{} must be 1..{} per side", name, w, h, kMaxSide)};
  if (!(image.resolution > 0.0) || !std::isfinite(image.resolution))
    return Error{fmt::format("map '{}': resolution {} must be a positive number", name, image.resolution)};
  if (!std::isfinite(image.origin.x) || !std::isfinite(image.origin.y))
    return Error{fmt::format("map '{}': origin is not finite", name)};
  if (image.occupied.size() != static_cast<size_t>(w) * static_cast<size_t>(h))
    return Error{
        fmt::format("map '{}': {} occupancy flags for a {}x{} image", name, image.occupied.size(), w, h)};

  const double res = image.resolution;
  const Vec2 o = image.origin;
  const auto occ = [&](int x, int y) { return image.occupied[static_cast<size_t>(y) * w + x] != 0; };
  std::vector<Segment> walls;

  // Horizontal grid line y = j separates rows j-1 and j; runs of differing pairs become one wall.
  for (int j = 1; j < h; ++j) {
    int run = -1;
    for (int i = 0; i <= w; ++i) {
      const bool edge = i < w && occ(i, j - 1) != occ(i, j);
      if (edge && run < 0) run = i;
      if (!edge && run >= 0) {
        walls.push_back({{o.x + run * res, o.y + j * res}, {o.x + i * res, o.y + j * res}});
        run = -1;
      }
    }
  }
  // Vertical grid line x = i separates columns i-1 and i.
  for (int i = 1; i < w; ++i) {
    int run = -1;
    for (int j = 0; j <= h; ++j) {
      const bool edge = j < h && occ(i - 1, j) != occ(i, j);
      if (edge && run < 0) run = j;
      if (!edge && run >= 0) {
        walls.push_back({{o.x + i * res, o.y + run * res}, {o.x + i * res, o.y + j * res}});
        run = -1;
      }
    }
  }
  const Bounds bounds{o, {o.x + w * res, o.y + h * res}};
  return World::create(std::move(name), bounds, std::move(walls), image);
}

}  // namespace slam::sim

// Map image with true walls over it (see map_overlay.hpp).
#include "eval/map_overlay.hpp"

#include <algorithm>
#include <cmath>

namespace slam::bench {
namespace {

constexpr uint8_t kFreeGrey = 255;
constexpr uint8_t kOccupiedGrey = 0;
constexpr uint8_t kUnknownGrey = 205;  // map_server's unknown

}  // namespace

viewer::RgbImage render_overlay(const MapImage& map, std::span<const LineLayer> layers, int pixels_per_cell) {
  const int k = std::max(1, pixels_per_cell);
  viewer::RgbImage image;
  image.width = static_cast<int>(map.width) * k;
  image.height = static_cast<int>(map.height) * k;
  image.bottom_up = true;  // row 0 is the lowest y, as in the map
  image.pixels.assign(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3, kUnknownGrey);
  for (int py = 0; py < image.height; ++py) {
    for (int px = 0; px < image.width; ++px) {
      const uint8_t cell = map.cells[static_cast<size_t>(py / k) * map.width + static_cast<size_t>(px / k)];
      const uint8_t grey = cell == kMapFree ? kFreeGrey : cell == kMapOccupied ? kOccupiedGrey : kUnknownGrey;
      const size_t at =
          (static_cast<size_t>(py) * static_cast<size_t>(image.width) + static_cast<size_t>(px)) * 3;
      std::fill_n(image.pixels.begin() + static_cast<std::ptrdiff_t>(at), 3, grey);
    }
  }
  const double pixel_m = map.resolution / k;
  for (const LineLayer& layer : layers) {
    for (const sim::Segment& s : layer.lines) {
      // Sample the line every half pixel: one-pixel-wide lines without gaps.
      const int n = std::max(1, static_cast<int>(std::ceil(2.0 * distance(s.a, s.b) / pixel_m)));
      for (int i = 0; i <= n; ++i) {
        const Vec2 p = s.a + (s.b - s.a) * (static_cast<double>(i) / n);
        const double fx = std::floor((p.x - map.origin_x) / pixel_m);
        const double fy = std::floor((p.y - map.origin_y) / pixel_m);
        if (fx < 0 || fy < 0 || fx >= image.width || fy >= image.height) continue;
        const size_t at =
            (static_cast<size_t>(fy) * static_cast<size_t>(image.width) + static_cast<size_t>(fx)) * 3;
        std::copy(layer.rgb.begin(), layer.rgb.end(), image.pixels.begin() + static_cast<std::ptrdiff_t>(at));
      }
    }
  }
  return image;
}

}  // namespace slam::bench

// Disk construction and layout reset for the inflation layer (the hot add/remove are inline).
#include "mapper/core/inflation.hpp"

#include <cmath>

namespace slam::mapper {

void InflationLayer::configure(double radius, double resolution) {
  disk_.clear();
  const double r = radius / resolution;
  const auto reach = static_cast<int32_t>(std::floor(r));
  for (int32_t dy = -reach; dy <= reach; ++dy)
    for (int32_t dx = -reach; dx <= reach; ++dx)
      if (static_cast<double>(dx * dx + dy * dy) <= r * r + 1e-9) disk_.push_back({dx, dy});
}

void InflationLayer::reset(int32_t width, int32_t height) {
  width_ = width;
  height_ = height;
  counts_.assign(static_cast<size_t>(width) * static_cast<size_t>(height), 0);
}

}  // namespace slam::mapper

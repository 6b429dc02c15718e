#include "pose_correction/likelihood_field.hpp"

#include <algorithm>
#include <cmath>

#include "common/core/cell_class.hpp"

namespace slam::correction {
namespace {

// The Gaussian is cut where it has fallen below 1 %: three sigma.
constexpr double kKernelReachSigmas = 3.0;

}  // namespace

void LikelihoodField::build_kernel(double resolution) {
  if (kernel_resolution_ == resolution && !kernel_.empty()) return;
  const double sigma_cells = sigma_m_ / resolution;
  kernel_radius_ = std::max(1, static_cast<int32_t>(std::ceil(kKernelReachSigmas * sigma_cells)));
  const int32_t span = 2 * kernel_radius_ + 1;
  kernel_.resize(static_cast<size_t>(span * span));
  for (int32_t dy = -kernel_radius_; dy <= kernel_radius_; ++dy)
    for (int32_t dx = -kernel_radius_; dx <= kernel_radius_; ++dx)
      kernel_[static_cast<size_t>((dy + kernel_radius_) * span + dx + kernel_radius_)] =
          static_cast<float>(std::exp(-(dx * dx + dy * dy) / (2.0 * sigma_cells * sigma_cells)));
  kernel_resolution_ = resolution;
}

Status LikelihoodField::build(const GridView& grid, const CellBox& box, size_t max_cells) {
  const GridGeometry& geo = grid.geometry;
  if (!(sigma_m_ > 0.0) || !std::isfinite(sigma_m_)) return Error{"likelihood field: sigma must be > 0"};
  if (box.empty()) return Error{"likelihood field: empty box"};
  if (box.cells() > max_cells) return Error{"likelihood field: the box spans too many cells"};
  build_kernel(geo.resolution);
  box_ = box;
  values_.assign(box.cells(), 0.0f);
  // Each occupied cell within kernel reach of the box stamps the maximum of its kernel: the Gaussian
  // of the distance to the nearest occupied cell.
  const int32_t fw = box.width, fh = box.height, r = kernel_radius_, span = 2 * r + 1;
  const int32_t gy0 = std::max(0, box.y0 - r), gy1 = std::min(geo.height, box.y0 + fh + r);
  const int32_t gx0 = std::max(0, box.x0 - r), gx1 = std::min(geo.width, box.x0 + fw + r);
  for (int32_t gy = gy0; gy < gy1; ++gy) {
    const uint8_t* row = grid.classes.data() + static_cast<size_t>(gy) * static_cast<size_t>(geo.width);
    for (int32_t gx = gx0; gx < gx1; ++gx) {
      if (!is_wall(row[gx])) continue;
      const int32_t cx = gx - box.x0, cy = gy - box.y0;
      const int32_t y_from = std::max(cy - r, 0), y_to = std::min(cy + r, fh - 1);
      const int32_t x_from = std::max(cx - r, 0), x_to = std::min(cx + r, fw - 1);
      for (int32_t y = y_from; y <= y_to; ++y) {
        float* out = values_.data() + static_cast<size_t>(y) * static_cast<size_t>(fw);
        const float* k = kernel_.data() + static_cast<size_t>((y - cy + r) * span);
        for (int32_t x = x_from; x <= x_to; ++x) out[x] = std::max(out[x], k[x - cx + r]);
      }
    }
  }
  return {};
}

}  // namespace slam::correction

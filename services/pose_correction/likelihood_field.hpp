#pragma once
// What a scan matcher scores points against: over a box of grid cells, the Gaussian of each cell's
// distance to the nearest occupied cell (1 on an occupied cell, falling to 0 three sigma away).
// Built only over the box a search reads, so its cost follows the keyframe, not the map.
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "pose_correction/grid_view.hpp"

namespace slam::correction {

class LikelihoodField {
 public:
  explicit LikelihoodField(double sigma_m = 0.05) : sigma_m_(sigma_m) {}

  // Fills the field over `box` (grid cells; it may reach beyond the grid, where nothing is occupied).
  // Refuses a box of more than `max_cells` cells, so a search cannot grow without bound.
  Status build(const GridView& grid, const CellBox& box, size_t max_cells);

  const CellBox& box() const { return box_; }
  std::span<const float> values() const { return values_; }  // row-major over box()
  int32_t width() const { return box_.width; }
  int32_t height() const { return box_.height; }
  // Likelihood at grid cell (x, y); 0 outside the box.
  float at(int32_t x, int32_t y) const {
    const int32_t fx = x - box_.x0, fy = y - box_.y0;
    if (fx < 0 || fy < 0 || fx >= box_.width || fy >= box_.height) return 0.0f;
    return values_[static_cast<size_t>(fy) * static_cast<size_t>(box_.width) + static_cast<size_t>(fx)];
  }

 private:
  void build_kernel(double resolution);

  double sigma_m_;
  std::vector<float> kernel_;     // likelihood by cell offset from an occupied cell, (2r + 1)^2
  int32_t kernel_radius_ = 0;     // r, cells
  double kernel_resolution_ = 0;  // the resolution kernel_ was built for
  CellBox box_;
  std::vector<float> values_;
};

}  // namespace slam::correction

#pragma once
// The picture of a run: the exported map (free white, occupied black, unknown grey) with lines
// drawn over it, the true walls above all, so doubled or displaced walls show at a glance.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/map_io.hpp"
#include "simulator/core/geometry.hpp"
#include "viewer/core/png_file.hpp"

namespace slam::bench {

struct LineLayer {
  std::vector<sim::Segment> lines;  // map frame
  std::array<uint8_t, 3> rgb{};
};

// The map at `pixels_per_cell` pixels per cell side, north up, with `layers` drawn in order.
viewer::RgbImage render_overlay(const MapImage& map, std::span<const LineLayer> layers, int pixels_per_cell);

}  // namespace slam::bench

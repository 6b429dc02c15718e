#pragma once
// When a re-render redraws only what moved (partial_rerender.hpp), and when it rebuilds the whole grid.
#include "common/core/result.hpp"

namespace slam::mapper {

struct RerenderOptions {
  double min_shift_cells = 0.25;   // a keyframe whose points move less than this (cells) is not redrawn
  double max_tile_fraction = 0.5;  // above this share of the grid's tiles, a full rebuild instead
};

// Ok, or the bad key with the reason ("rerender.min_shift_cells: must be >= 0, got -1").
Status validate(const RerenderOptions& options);

}  // namespace slam::mapper

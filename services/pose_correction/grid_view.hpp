#pragma once
// A read-only view of occupancy class octets (map.idl's cell classes) with their geometry: what the
// scan matcher reads. The mapper's grid and the loop closer's small local grids both provide one.
#include <cstdint>
#include <span>

#include "common/core/geometry.hpp"

namespace slam::correction {

struct GridView {
  GridGeometry geometry;
  std::span<const uint8_t> classes;  // row-major, geometry.width * geometry.height
  // What a hit in a cell never observed (unknown, or outside the grid) and away from walls is worth
  // to the matcher, 0..1: a hit on a wall is worth 1, one in known free space 0. Above 0 only for a
  // view that tells free from unobserved (the mapper's grid; a local grid drawn from keyframe points
  // knows walls only). Why: at a frontier the map's walls end where the robot stopped seeing them,
  // not where they end, and at 0 a keyframe reaching past that edge gains by sliding back onto the
  // mapped part, so tracking drags an exploring robot backwards (docs/mapping-quality.md).
  double unobserved_likelihood = 0.0;
};

}  // namespace slam::correction

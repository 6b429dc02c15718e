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
};

}  // namespace slam::correction

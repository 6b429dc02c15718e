#pragma once
// One entry point for "which world": a built-in name, a ROS map_server map (.yaml/.yml naming a
// PGM) or a Java server world text file (any other path).
#include <string_view>

#include "common/core/map_io.hpp"
#include "common/core/result.hpp"
#include "simulator/core/world.hpp"

namespace slam::sim {

// Occupied map cells become walls (see world_from_image); unknown cells count as free. A rotated
// map (origin yaw != 0) is refused: world bounds are axis-aligned.
Result<World> world_from_map(const MapImage& map, std::string name);

// Errors name the spec and what went wrong (unknown name, unreadable file, bad token, ...).
Result<World> load_world(std::string_view spec);

}  // namespace slam::sim

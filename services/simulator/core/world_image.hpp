#pragma once
// Worlds from occupancy images (a ROS map_server map once read): the exposed edges of occupied
// cells become walls, merged along rows and columns so a straight wall is one segment, not one per
// cell. The image border is the world border.
#include <string>

#include "common/core/result.hpp"
#include "simulator/core/world.hpp"

namespace slam::sim {

// The image also becomes the world's solid mask, so no robot is placed inside a filled region.
// Errors name `name` and the bad field (size, resolution, origin, flag count).
Result<World> world_from_image(const OccupancyImage& image, std::string name);

}  // namespace slam::sim

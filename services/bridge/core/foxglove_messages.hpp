#pragma once
// The fleet model as JSON messages of Foxglove's own schemas (foxglove.Grid, foxglove.SceneUpdate,
// foxglove.FrameTransforms, foxglove.PointCloud) and of the bridge's own (slam.ServiceHealth, slam.Alerts).
// Everything is in the "map" frame; each robot is also a frame named after its id.
#include <cstdint>
#include <span>
#include <string>

#include "bridge/core/fleet_model.hpp"
#include "common/core/geometry.hpp"

namespace slam::bridge {

inline constexpr const char* kMapFrame = "map";

struct Rgba {
  double r = 0.0, g = 0.0, b = 0.0, a = 1.0;
};

// A robot's colour: a hue from its id, the same in every client and after every restart.
Rgba robot_color(const std::string& robot_id);

// A cell class (common/core/cell_class.hpp) as the int8 occupancy of a ROS map: -1 unknown, 0 free,
// 50 free but within a robot's radius of an obstacle, 100 occupied or obstructed.
int8_t occupancy_of(uint8_t cell);

// `box` of the grid (the whole grid or the changed region) as a foxglove.Grid of one INT8 field
// "occupancy", placed at the box's lower-left corner.
std::string grid_message(const GridGeometry& geometry, std::span<const uint8_t> cells, const CellBox& box,
                         int64_t stamp_ns);

// One entity per robot: an arrow along its heading (a sphere when it reports none), its name above.
// Offline robots are drawn faded.
std::string robots_message(const FleetModel& fleet, int64_t stamp_ns);

// map -> robot for every robot with a state.
std::string transforms_message(const FleetModel& fleet, int64_t stamp_ns);

// One entity per robot with a path: the remaining waypoints as a line from the robot, its target
// as a sphere. A robot whose goal is over (or has none) gets an empty entity, which clears it.
std::string paths_message(const FleetModel& fleet, int64_t stamp_ns);

// Every robot's recent measurement points as one cloud (x, y, z float32).
std::string points_message(const FleetModel& fleet, int64_t stamp_ns);

// Every service heard in heartbeats, with the seconds since it was last heard.
std::string health_message(const FleetModel& fleet, int64_t now_mono_ns, int64_t stamp_ns);

// Every alert the planners raised, active or cleared (slam.Alerts).
std::string alerts_message(const FleetModel& fleet, int64_t stamp_ns);

}  // namespace slam::bridge

#pragma once
// A robot's trajectory out of the observation store: each stored observation of the robot placed in
// the map frame by its keyframe's stored correction, written as TUM or CARMEN text for trajectory
// tools (evo, the TUM RGB-D scripts, CARMEN log readers). Plain C++ on the store: the running mapper
// answers a MapFileRequest with it, and `slam-mapper --export-trajectory` reads a stopped fleet's.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "mapper/core/map_files.hpp"
#include "mapper/core/observation_store.hpp"

namespace slam::mapper {

enum class TrajectoryFormat {
  Tum,     // "stamp x y z qx qy qz qw": stamp in seconds, z = 0, the quaternion of the yaw
  Carmen,  // "ODOM x y theta tv rv accel stamp host logger_stamp", velocities 0, host "slamfleet"
};

// "tum" or "carmen"; nullopt for anything else.
std::optional<TrajectoryFormat> trajectory_format_named(std::string_view name);

struct TrajectoryPose {
  int64_t stamp_ns = 0;      // the robot's clock when the robot sent a stamp, else the gateway's arrival time
  Pose pose;                 // map frame: the keyframe's correction composed with the odometry pose
  bool has_heading = false;  // false (v1 robots): the robot reported none and pose.theta is 0
};

// Every stored observation of `robot`, in store order. One without a stored keyframe correction (SLAM
// off, a store older than keyframes) is placed by the correction of the robot's nearest keyframe
// before it in the store, or the identity before any. Empty when the store holds none of the robot's.
// The pose is the observation's: a scan's is its sensor origin (docs/protocol.md).
Result<std::vector<TrajectoryPose>> robot_trajectory(ObservationStore& store, std::string_view robot);

// Writes one line per pose to `path` (replaced); errors name the path.
Status write_trajectory(std::span<const TrajectoryPose> poses, const std::filesystem::path& path,
                        TrajectoryFormat format);

// A trajectory request: `robot`'s trajectory written to `path` on this machine, failures sorted as a
// MapReply needs them: an empty path or a NUL in it is InvalidRequest, a robot without stored
// observations UnknownRobot, a missing directory or a failed write Io (a remote request never creates
// directories). The message says how many poses were written and their first and last stamps.
FileOutcome export_trajectory_file(ObservationStore& store, std::string_view robot, const std::string& path,
                                   TrajectoryFormat format);

}  // namespace slam::mapper

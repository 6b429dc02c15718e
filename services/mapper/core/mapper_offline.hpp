#pragma once
// slam-mapper's offline commands: --export (rebuild from the store, write a ROS map), --import
// (store a ROS map as the prior) and --export-trajectory (one robot's corrected trajectory as TUM or
// CARMEN text). No DDS: they work on a store no mapper has open, e.g. for backups, to seed a new
// site's map before the fleet starts, or to evaluate a stopped fleet's run.
#include <string>

#include "common/core/result.hpp"
#include "mapper/core/mapper_options.hpp"

namespace slam::mapper {

// Runs the command `options` names; returns a one-line summary, or an error naming the file.
Result<std::string> run_offline(const MapperOptions& options);

}  // namespace slam::mapper

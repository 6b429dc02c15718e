#pragma once
// Any robot log this library reads, chosen by content: a file starting with the MCAP magic is a
// ROS 2 recording, anything else a CARMEN log (plain or gzip).
#include <filesystem>

#include "common/core/result.hpp"
#include "simulator/robot_log/carmen_line.hpp"
#include "simulator/robot_log/robot_log.hpp"
#include "simulator/robot_log/ros2_mcap_log.hpp"

namespace slam::robot_log {

struct ReadOptions {
  CarmenOptions carmen;
  Ros2McapOptions ros2;
};

enum class LogFormat : uint8_t { Carmen, Ros2Mcap };

// The format of the file at `path` (from its first bytes); an error when it cannot be read.
Result<LogFormat> detect_log_format(const std::filesystem::path& path);

Result<RobotLog> read_robot_log(const std::filesystem::path& path, const ReadOptions& options = {});

}  // namespace slam::robot_log

// Fuzz target for the ROS 2 recording reader: the bytes as each of the three CDR messages it decodes,
// and as an MCAP file read into scans. Any input gives values or errors, never a crash; kept scans
// are finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "common/core/mcap_reader.hpp"
#include "simulator/robot_log/ros2_mcap_log.hpp"
#include "simulator/robot_log/ros2_messages.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace rl = slam::robot_log;
  const std::span<const uint8_t> input(data, size);
  (void)rl::decode_laser_scan(input);
  (void)rl::decode_odometry(input);
  (void)rl::decode_tf_message(input);
  const auto contents = slam::mcap::parse(input);
  if (!contents) return 0;
  const auto log = rl::ros2_log_from_mcap(*contents);
  if (!log) return 0;
  if (log->stats.scans != static_cast<int64_t>(log->scans.size())) __builtin_trap();
  for (const rl::LaserScan& s : log->scans)
    if (!std::isfinite(s.stamp_s + s.odom.x + s.odom.theta + s.laser_in_robot.theta + s.angle_min_rad))
      __builtin_trap();
  return 0;
}

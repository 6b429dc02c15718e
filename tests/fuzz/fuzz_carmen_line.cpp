// Fuzz target for the CARMEN log reader: any bytes, split into lines, give scans and counts, never
// a crash; every kept scan is finite and its counts add up.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "simulator/robot_log/carmen_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto log = slam::robot_log::parse_carmen_text(text);
  const auto& s = log.stats;
  if (s.scans != static_cast<int64_t>(log.scans.size())) __builtin_trap();
  if (s.scans + s.odometry + s.comments + s.unknown_kinds + s.bad_lines > s.lines) __builtin_trap();
  if ((s.bad_lines > 0) == s.first_bad.empty()) __builtin_trap();
  for (const auto& scan : log.scans) {
    const double sum = scan.stamp_s + scan.odom.x + scan.odom.y + scan.odom.theta + scan.laser_in_robot.x +
                       scan.laser_in_robot.theta + scan.angle_min_rad + scan.angle_increment_rad +
                       scan.max_range_m;
    if (!std::isfinite(sum) || !(scan.max_range_m > 0)) __builtin_trap();
    for (size_t i = 0; i < scan.ranges.size(); ++i) (void)scan.is_return(i);
  }
  return 0;
}

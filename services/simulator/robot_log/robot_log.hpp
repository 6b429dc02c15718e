#pragma once
// What a recorded robot log holds once read, whatever its file format (CARMEN text, ROS 2 MCAP):
// laser scans in file order, each with the robot's odometry pose at the scan, and counts of what
// the reader met on the way (bad lines are skipped and counted, never fatal; readings that say
// nothing and stamps out of order are kept as they are and counted).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::robot_log {

struct LaserScan {
  double stamp_s = 0;              // the robot's clock (CARMEN: ipc_timestamp; ROS 2: header.stamp)
  Pose odom;                       // the robot's odometry pose at the scan
  Pose laser_in_robot;             // the sensor's mount on the robot
  double angle_min_rad = 0;        // beam 0, in the sensor frame
  double angle_increment_rad = 0;  // counter-clockwise step between beams
  double max_range_m = 0;          // a reading >= this (or <= 0, or not finite) is "no return"
  std::vector<float> ranges;       // metres, counter-clockwise

  // Whether beam i hit something.
  bool is_return(size_t i) const {
    const float r = ranges[i];
    return r > 0.0f && r < max_range_m;  // false for NaN too
  }
};

struct LogStats {
  int64_t lines = 0;          // records (lines or messages) read
  int64_t scans = 0;          // kept as LaserScan
  int64_t odometry = 0;       // wheel odometry records (scans carry their own odometry pose)
  int64_t comments = 0;       // '#' and empty lines
  int64_t unknown_kinds = 0;  // well-formed records of a kind the reader does not use
  int64_t bad_lines = 0;    // skipped: wrong field counts, non-numbers, a scan without a finite pose or stamp
  int64_t stamps_back = 0;  // scans stamped earlier than the scan before (kept in file order)
  int64_t stamp_jumps = 0;  // scans stamped over kStampJumpS before or after the scan before
  // Readings (beams) of the kept scans that say nothing: NaN, -inf, <= 0, below a ROS sensor's
  // range_min. Kept as they are (LaserScan::is_return is false); the player leaves them out.
  int64_t error_readings = 0;
  int64_t far_readings = 0;  // readings at or beyond the scan's max_range (+inf included): no return
  std::string first_bad;     // "line N: reason" for the first bad line; empty when none
};

struct RobotLog {
  std::vector<LaserScan> scans;  // in file order
  LogStats stats;
};

// A step between two consecutive scans' stamps larger than this (either way) is no pause of the
// robot but its clock set, or a recording stopped and resumed: the player does not wait it out.
inline constexpr double kStampJumpS = 60.0;

// Counts a scan the reader keeps: its readings, and its stamp against `previous` (the scan kept
// before it; null for the first).
inline void count_scan(const LaserScan& scan, const LaserScan* previous, LogStats& stats) {
  ++stats.scans;
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!(r > 0.0f)) {
      ++stats.error_readings;
    } else if (!(r < scan.max_range_m)) {
      ++stats.far_readings;
    }
  }
  if (previous == nullptr) return;
  const double step = scan.stamp_s - previous->stamp_s;
  if (step < 0) ++stats.stamps_back;
  if (std::abs(step) > kStampJumpS) ++stats.stamp_jumps;
}

}  // namespace slam::robot_log

#pragma once
// One line of a CARMEN text log (the Freiburg benchmark's .clf files): which kind of record it is
// and, for a laser line, the scan it carries. Plain text in, a value or an error out; the reader
// (carmen_log.hpp) counts and skips the errors.
//
// Kinds used: FLASER / RLASER (front / rear laser, no angles: 180 degrees from -90 degrees),
// ROBOTLASER1 (explicit angles, maximum range, laser and robot poses), ODOM (counted) and
// PARAM robot_frontlaser_offset / robot_rearlaser_offset (the laser's x on the robot, for the
// FLASER / RLASER lines that follow).
//
// A laser line's readings may be "nan" (an error reading) or "inf" (no return), as logs converted
// from ROS write them: the scan is kept and the reader counts them. Its pose and stamp fields must
// be finite numbers: a scan without a usable pose is an error (the reader skips and counts it).
#include <optional>
#include <string_view>

#include "common/core/result.hpp"
#include "simulator/robot_log/robot_log.hpp"

namespace slam::robot_log {

struct CarmenOptions {
  // FLASER and RLASER carry no maximum range: readings at or beyond this are "no return" (the
  // benchmark's lasers read 81.91 m for nothing).
  double flaser_max_range_m = 81.0;

  Status validate() const;
};

// What earlier lines said that later ones need.
struct CarmenContext {
  double front_laser_offset_m = 0;  // PARAM robot_frontlaser_offset
  double rear_laser_offset_m = 0;   // PARAM robot_rearlaser_offset
};

enum class CarmenKind : uint8_t { Comment, Scan, Odometry, Param, Unknown };

struct CarmenRecord {
  CarmenKind kind = CarmenKind::Comment;
  std::optional<LaserScan> scan;  // kind == Scan
};

// Parses one line (without its newline); a PARAM line the reader knows updates `context`.
// Fields are separated by spaces or tabs; a trailing '\r' is ignored.
Result<CarmenRecord> parse_carmen_line(std::string_view line, CarmenContext& context,
                                       const CarmenOptions& options = {});

}  // namespace slam::robot_log

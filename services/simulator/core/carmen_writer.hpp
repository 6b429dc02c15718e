#pragma once
// A simulated robot's scan as CARMEN log text, the kind robot_log/carmen_line.hpp reads back. Each
// scan is a ROBOTLASER1 line, not FLASER: FLASER implies 180 degrees from -90 degrees, while the
// simulated sensor sees all around by default (config.hpp), so the line states the beams' start
// angle, step and maximum range itself. Plain text out; log_recorder.hpp owns the files.
#include <string>
#include <string_view>

#include "simulator/core/report.hpp"

namespace slam::sim {

// Seconds with six decimals. The log and its relation file write every stamp through this, so a
// relation's stamps equal its scans' as text, and so to the microsecond once read back.
std::string stamp_text(double seconds);

// The comment lines that open a robot's log: what wrote it and how to read it.
std::string carmen_header(std::string_view robot_id, std::string_view world);

// Appends one line:
//   ROBOTLASER1 0 start fov step max_range 0 0 n r1..rn 0 laser_x laser_y laser_theta x y theta
//   0 0 0 0 0 stamp slamsim stamp
// with the robot at its reported (odometry) pose, the laser at its sensor mount (the centre when
// none), fov the span from the first beam to the last, and the simulated time as the stamps.
// The beams must be evenly spaced (as beam_angles lays them out, full turns aside); a range equal to
// max_range is no return.
void append_robotlaser_line(const RobotReport& report, std::string& out);

}  // namespace slam::sim

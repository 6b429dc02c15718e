// CARMEN text of simulated scans (carmen_writer.hpp).
#include "simulator/core/carmen_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

namespace slam::sim {

namespace {

constexpr std::string_view kHost = "slamsim";
constexpr double kRangeResolution = 1e-4;  // ranges are written with four decimals

}  // namespace

std::string stamp_text(double seconds) {
  return fmt::format("{:.6f}", seconds);
}

std::string carmen_header(std::string_view robot_id, std::string_view world) {
  return fmt::format(
      "# CARMEN log written by slam-simulator --record-log: robot {} in world {}\n"
      "# ROBOTLASER1 lines: the robot's odometry pose (it drifts) and the simulated beams; stamps are\n"
      "# simulated seconds. Ground truth is in the matching .relations file.\n",
      robot_id, world);
}

void append_robotlaser_line(const RobotReport& report, std::string& out) {
  const size_t n = report.angles.size();
  const double start = n > 0 ? report.angles[0] : 0.0;
  // The step modulo a full turn: a full circle's beams wrap from +pi to -pi half-way round.
  const double step = n > 1 ? wrap_angle(report.angles[1] - report.angles[0]) : 0.0;
  const double fov = n > 1 ? step * static_cast<double>(n - 1) : 0.0;
  const Pose& robot = report.reported_pose;
  const Pose laser = robot.compose(report.sensor.value_or(Pose{}));
  // The reader keeps ranges as floats and compares them with the maximum as a double: both are
  // written as the float nearest the maximum, so a no-return reads back as exactly the maximum.
  const double max_range = static_cast<float>(report.max_range);
  auto at = std::back_inserter(out);
  fmt::format_to(at, "ROBOTLASER1 0 {:.9f} {:.9f} {:.9f} {} 0 0 {}", start, fov, step, max_range, n);
  for (size_t i = 0; i < n; ++i) {
    const double r = report.ranges[i];
    if (r >= report.max_range) {
      fmt::format_to(at, " {}", max_range);
      continue;
    }
    // A hit just short of the maximum must not round up to it and read back as no return.
    fmt::format_to(at, " {:.4f}", std::min(r, max_range - kRangeResolution));
  }
  const std::string stamp = stamp_text(report.time_s);
  fmt::format_to(at, " 0 {:.6f} {:.6f} {:.9f} {:.6f} {:.6f} {:.9f} 0 0 0 0 0 {} {} {}\n", laser.x, laser.y,
                 laser.theta, robot.x, robot.y, robot.theta, stamp, kHost, stamp);
}

}  // namespace slam::sim

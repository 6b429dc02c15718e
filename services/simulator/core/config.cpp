// Range checks for the simulation parameters, so a bad flag or config key fails at start.
#include "simulator/core/config.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string_view>

namespace slam::sim {
namespace {

// Error unless lo <= v <= hi (NaN fails).
Status in_range(std::string_view key, double v, double lo, double hi) {
  if (v >= lo && v <= hi) return {};
  return Error{fmt::format("{} = {} is out of range [{}, {}]", key, v, lo, hi)};
}

// Error unless 0 < v <= hi.
Status positive(std::string_view key, double v, double hi) {
  if (v > 0.0 && v <= hi) return {};
  return Error{fmt::format("{} = {} must be in (0, {}]", key, v, hi)};
}

}  // namespace

Status validate(const RobotConfig& c) {
  for (auto s : {positive("robot.radius", c.radius, 10.0), positive("robot.max_linear", c.max_linear, 100.0),
                 positive("robot.max_angular", c.max_angular, 100.0),
                 positive("robot.waypoint_tolerance", c.waypoint_tolerance, 10.0),
                 in_range("robot.turn_in_place_above", c.turn_in_place_above, 0.0, std::numbers::pi)})
    if (!s) return s;
  return {};
}

Status validate(const SensorConfig& c) {
  if (c.beams < 0 || c.beams > 4096)
    return Error{fmt::format("sensor.beams = {} is out of range [0, 4096]", c.beams)};
  for (auto s : {positive("sensor.fov", c.fov, 2.0 * std::numbers::pi),
                 positive("sensor.max_range", c.max_range, 1000.0),
                 in_range("sensor.range_noise_sd", c.range_noise_sd, 0.0, 10.0),
                 in_range("sensor.dropout", c.dropout, 0.0, 1.0)})
    if (!s) return s;
  return {};
}

Status validate(const OdometryConfig& c) {
  if (auto s = in_range("odometry.drift_per_metre", c.drift_per_metre, 0.0, 10.0); !s) return s;
  return in_range("odometry.drift_per_radian", c.drift_per_radian, 0.0, 10.0);
}

Status validate(const SimulationConfig& c) {
  for (auto s : {positive("dt", c.dt, 1.0), positive("report_period", c.report_period, 3600.0),
                 positive("speed_factor", c.speed_factor, 1000.0)})
    if (!s) return s;
  if (auto s = validate(c.robot); !s) return s;
  if (auto s = validate(c.sensor); !s) return s;
  if (auto s = validate(c.odometry); !s) return s;
  // Robot-robot checks look at step ends only: a longer step could pass through another robot.
  if (c.robot.max_linear * c.dt > c.robot.radius)
    return Error{fmt::format("dt = {} s lets a robot move {} m per step, more than its radius {} m", c.dt,
                             c.robot.max_linear * c.dt, c.robot.radius)};
  return {};
}

}  // namespace slam::sim

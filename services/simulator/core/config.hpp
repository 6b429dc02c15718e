#pragma once
// Simulation parameters as plain structs with defaults, and validators that name the bad key.
#include <cstdint>
#include <numbers>

#include "common/core/result.hpp"

namespace slam::sim {

struct RobotConfig {
  double radius = 0.15;              // m, collision disc
  double max_linear = 0.5;           // m/s
  double max_angular = 2.0;          // rad/s
  double waypoint_tolerance = 0.05;  // m: closer than this counts as arrived
  double turn_in_place_above = 0.5;  // rad: larger heading errors are turned out before driving
};

struct SensorConfig {
  int beams = 16;
  double fov = 2.0 * std::numbers::pi;  // rad, centred on the heading; 2*pi = all around
  double max_range = 4.0;               // m; a range equal to it means "no hit"
  double range_noise_sd = 0.01;         // m, Gaussian, added to every hit
  double dropout = 0.0;                 // probability a beam returns nothing
};

// Drift is a random walk: after driving d metres the position error has a standard deviation of
// drift_per_metre * sqrt(d) along and across the path (independent of the step size); turning adds
// heading error the same way.
struct OdometryConfig {
  double drift_per_metre = 0.02;   // m per sqrt(m) driven
  double drift_per_radian = 0.01;  // rad per sqrt(rad) turned
};

// Where a robot's odometry frame is: World puts its origin at the world's, so a robot starts
// believing its true spawn pose; Start puts it at the robot's own spawn pose, so it starts at
// (0, 0, 0) as a real robot does. Every reported pose, obstacle point and waypoint is in that frame.
enum class OdomFrame : uint8_t { World, Start };

struct SimulationConfig {
  double dt = 0.05;            // s of simulated time per step
  double report_period = 0.1;  // s between a robot's reports (10 Hz)
  double speed_factor = 1.0;   // simulated seconds per wall-clock second
  uint64_t seed = 1;           // robot k's generator is seeded from (seed, k)
  bool random_walk = false;    // idle robots pick random reachable targets
  OdomFrame odom_frame = OdomFrame::World;
  RobotConfig robot;
  SensorConfig sensor;
  OdometryConfig odometry;
};

// Each returns the first bad key with its value and the accepted range.
Status validate(const RobotConfig& c);
Status validate(const SensorConfig& c);
Status validate(const OdometryConfig& c);
Status validate(const SimulationConfig& c);

}  // namespace slam::sim

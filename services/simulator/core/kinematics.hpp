#pragma once
// Unicycle motion: the waypoint controller (run on the pose the robot believes, as a real robot
// would), pose integration, and odometry that accumulates drift while the true pose stays exact.
#include <random>

#include "simulator/core/config.hpp"
#include "simulator/core/geometry.hpp"

namespace slam::sim {

struct Twist {
  double linear = 0.0;   // m/s
  double angular = 0.0;  // rad/s
};

// Command that drives `believed` toward `target` within one step of dt: turn in place while the
// heading error exceeds turn_in_place_above, else drive (slowing so it stops on the target) while
// steering; limited to the configured speeds.
Twist drive_command(const Pose& believed, Vec2 target, double dt, const RobotConfig& c);

// Pose after moving with `cmd` for dt (midpoint heading, exact for straight lines and turns).
Pose integrate(const Pose& p, Twist cmd, double dt);

// The believed pose after the robot truly moved from `before` to `after`: the motion is expressed
// in the robot's frame, perturbed as OdometryConfig describes, and applied to `believed`.
Pose odometry_update(const Pose& believed, const Pose& before, const Pose& after, const OdometryConfig& c,
                     std::mt19937_64& rng);

}  // namespace slam::sim

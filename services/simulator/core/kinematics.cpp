// Controller, integration and odometry noise for one robot. Pure functions: the fleet decides
// what motion collisions allow and keeps the state.
#include "simulator/core/kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace slam::sim {

Twist drive_command(const Pose& believed, Vec2 target, double dt, const RobotConfig& c) {
  const Vec2 to = target - Vec2{believed.x, believed.y};
  const double dist = norm(to);
  const double err = wrap_angle(std::atan2(to.y, to.x) - believed.theta);
  // Proportional heading gain, bounded so one step never turns past the target bearing.
  const double gain = std::min(3.0, 1.0 / dt);
  Twist cmd;
  cmd.angular = std::clamp(gain * err, -c.max_angular, c.max_angular);
  if (std::abs(err) <= c.turn_in_place_above)
    cmd.linear = std::min(c.max_linear, dist / dt) * std::max(0.0, std::cos(err));
  return cmd;
}

Pose integrate(const Pose& p, Twist cmd, double dt) {
  const double mid = p.theta + 0.5 * cmd.angular * dt;
  return {p.x + cmd.linear * dt * std::cos(mid), p.y + cmd.linear * dt * std::sin(mid),
          wrap_angle(p.theta + cmd.angular * dt)};
}

Pose odometry_update(const Pose& believed, const Pose& before, const Pose& after, const OdometryConfig& c,
                     std::mt19937_64& rng) {
  // True motion in the robot's frame at `before`.
  const double dx = after.x - before.x, dy = after.y - before.y;
  const double cs = std::cos(before.theta), sn = std::sin(before.theta);
  double fwd = cs * dx + sn * dy;
  double side = -sn * dx + cs * dy;
  double turn = wrap_angle(after.theta - before.theta);
  const double dist = std::hypot(dx, dy);
  std::normal_distribution<double> unit(0.0, 1.0);
  if (c.drift_per_metre > 0.0 && dist > 0.0) {
    const double sd = c.drift_per_metre * std::sqrt(dist);
    fwd += sd * unit(rng);
    side += sd * unit(rng);
  }
  if (c.drift_per_radian > 0.0 && turn != 0.0)
    turn += c.drift_per_radian * std::sqrt(std::abs(turn)) * unit(rng);
  // Apply the measured motion in the believed frame.
  const double bc = std::cos(believed.theta), bs = std::sin(believed.theta);
  return {believed.x + bc * fwd - bs * side, believed.y + bs * fwd + bc * side,
          wrap_angle(believed.theta + turn)};
}

}  // namespace slam::sim

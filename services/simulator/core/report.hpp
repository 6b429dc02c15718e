#pragma once
// What a simulated robot reports, carrying everything both robot protocols need: v1 sends the
// believed position then the obstacle points; v2 adds the heading and the polar scan. Encoding is
// the gateway codecs' job; the simulator only fills this.
#include <optional>
#include <string>
#include <vector>

#include "simulator/core/geometry.hpp"

namespace slam::sim {

struct RobotReport {
  std::string robot_id;
  double time_s = 0.0;  // simulated time of the measurement
  Pose reported_pose;   // odometry estimate (drifts); the frame of `hits` and of v1/v2 positions
  Pose true_pose;       // ground truth, for the truth topic only
  // Obstacle points in the map frame as the robot believes them: beam end points placed from
  // reported_pose, so odometry drift shows in the map the way it would with a real robot.
  std::vector<Vec2> hits;
  // Polar scan relative to the robot: angle (rad, from the heading) and range (m) per beam, in beam
  // order; range == max_range means the beam saw nothing.
  std::vector<double> angles;
  std::vector<double> ranges;
  double max_range = 0.0;
  // Where the sensor sits on the robot (v2 "sensor"); `angles` are then in the sensor's frame. The
  // simulated robots' sensor is at their centre; recorded logs (the player) know their mount.
  std::optional<Pose> sensor;
};

}  // namespace slam::sim

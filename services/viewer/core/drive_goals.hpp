#pragma once
// What the Drive tab's buttons send, as pure functions so tests check them without ImGui: a goal
// to the manual target, the calibration square around it, and a goal to one corner of that square.
#include <array>
#include <string>

#include "viewer/core/commands.hpp"

namespace slam::viewer {

// The Drive tab's choices that shape its goals.
struct DriveSettings {
  std::string robot_id = "*";  // the selected robot; "*" every robot
  Vec2 target;                 // the manual target, which is also the square's corner or centre
  double square_size = 1.0;    // metres
  bool square_centred = false;
};

// A goal in `mode` with the target and square settings (stop, home, explore and idle ignore both).
GoalCommand drive_goal(const DriveSettings& s, GoalMode mode);

// One goal per corner of the square, in its driving order (square_corners()): the robot drives
// straight to that corner (Direct) or along a planned path (Planned).
std::array<GoalCommand, 4> corner_goals(const DriveSettings& s, bool planned);

// For the status line: "planned goal to (1.00, 2.00) for every robot",
// "square goal (2.00 m, centred on (1.00, 2.00)) for r1", "stop goal for r1".
std::string describe(const GoalCommand& g);

}  // namespace slam::viewer

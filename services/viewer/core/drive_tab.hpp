#pragma once
// The Drive tab's controls without ImGui: the manual target (typed or taken from the selected
// robot), goals in any mode to the selected robot or every robot, the calibration square's size
// and anchor, and one goal per corner. The goals themselves come from drive_goals.hpp.
#include <cstddef>
#include <string>

#include "viewer/core/drive_goals.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

inline constexpr double kMinSquareSide = 0.1;  // metres

struct DriveTab {
  Vec2 target;
  bool planned_corners = false;  // corner buttons send planned (else direct) goals
  std::string error;             // the last refused input, shown in red

  // The goal settings as they stand: selected robot, target, square.
  DriveSettings settings(const ViewerState& state) const;
  // Copies the selected robot's position into the target; an error when no single robot with a
  // known pose is selected.
  void use_robot_position(ViewerState& state);
  // A goal in `mode` (direct, planned, square to the target; stop, home, explore, idle).
  void drive(ViewerState& state, CommandSink& sink, GoalMode mode);
  // A direct or planned goal to corner `index` (0..3, driving order) of the square.
  void drive_corner(ViewerState& state, CommandSink& sink, size_t index);
  // The square's side, at least kMinSquareSide (non-finite input is ignored).
  static void set_square_side(ViewerState& state, double side_m);
  static void set_square_centred(ViewerState& state, bool centred) { state.square_centred = centred; }

 private:
  void send(ViewerState& state, CommandSink& sink, const GoalCommand& goal);
};

}  // namespace slam::viewer

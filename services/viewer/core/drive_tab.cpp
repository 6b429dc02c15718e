// Drive tab actions (see drive_tab.hpp).
#include "viewer/core/drive_tab.hpp"

#include <cmath>

namespace slam::viewer {

DriveSettings DriveTab::settings(const ViewerState& state) const {
  return DriveSettings{state.selected_robot, target, state.square_size, state.square_centred};
}

void DriveTab::use_robot_position(ViewerState& state) {
  const RobotView* r = state.robots.find(state.selected_robot);
  if (!r || !r->has_state) {
    error = "select one robot whose position is known";
    return;
  }
  target = {r->state.pose.x, r->state.pose.y};
  error.clear();
}

void DriveTab::send(ViewerState& state, CommandSink& sink, const GoalCommand& goal) {
  if (!std::isfinite(goal.target.x) || !std::isfinite(goal.target.y)) {
    error = "the target must be finite";
    return;
  }
  state.note_sent(sink.send(goal), describe(goal), error);
}

void DriveTab::drive(ViewerState& state, CommandSink& sink, GoalMode mode) {
  send(state, sink, drive_goal(settings(state), mode));
}

void DriveTab::drive_corner(ViewerState& state, CommandSink& sink, size_t index) {
  if (index >= 4) {
    error = "a square has corners 1..4";
    return;
  }
  send(state, sink, corner_goals(settings(state), planned_corners)[index]);
}

void DriveTab::set_square_side(ViewerState& state, double side_m) {
  if (std::isfinite(side_m)) state.square_size = side_m < kMinSquareSide ? kMinSquareSide : side_m;
}

}  // namespace slam::viewer

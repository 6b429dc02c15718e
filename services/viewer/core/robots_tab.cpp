// Robots tab actions (see robots_tab.hpp).
#include "viewer/core/robots_tab.hpp"

namespace slam::viewer {

void RobotsTab::send_default_mode(ViewerState& state, CommandSink& sink) {
  const GoalMode mode = state.robots.defaults().mode;
  state.note_sent(sink.send(GoalCommand{"*", mode, {}, state.square_size, state.square_centred}),
                  std::string(goal_mode_name(mode)) + " goal for every robot", error);
}

void RobotsTab::send_robot_mode(ViewerState& state, CommandSink& sink, const RobotView& r) {
  const Vec2 target = r.has_path ? r.path.target : Vec2{r.state.pose.x, r.state.pose.y};
  state.note_sent(
      sink.send(GoalCommand{r.id, r.settings.mode, target, state.square_size, state.square_centred}),
      std::string(goal_mode_name(r.settings.mode)) + " goal for " + r.id, error);
}

void RobotsTab::reset_robot(ViewerState& state, CommandSink& sink, RobotView& r) {
  if (state.note_sent(sink.send(MapEditCommand{MapEditKind::ResetRobot, {}, r.id}), "reset of " + r.id,
                      error))
    r.points.reset();
}

void RobotsTab::answer_placement(ViewerState& state, CommandSink& sink, const RobotView& r, bool accept) {
  state.note_sent(sink.send(PlacementAnswerCommand{r.id, accept}),
                  std::string(accept ? "accept placement of " : "reject placement of ") + r.id, error);
}

void RobotsTab::forget_robot(ViewerState& state, CommandSink& sink, const RobotView& r) {
  state.note_sent(sink.send(ForgetCommand{r.id}), "forget " + r.id, error);
}

}  // namespace slam::viewer

// Manual drive tab (the 2019 calibration drive): a square path of a given size with the target as
// its corner or centre, or a manual target, for the selected robot or all.
#include <imgui.h>

#include "viewer/panels.hpp"

namespace slam::viewer {

void DrivePanel::draw(ViewerState& state, CommandSink& sink) {
  robot_selector(state, "robot");
  section_title("Target (map frame, metres)");
  ImGui::InputDouble("x", &target_x, 0.1, 1.0, "%.2f");
  ImGui::InputDouble("y", &target_y, 0.1, 1.0, "%.2f");
  if (ImGui::Button("use the selected robot's position")) {
    if (RobotView* r = state.robots.find(state.selected_robot); r && r->has_state) {
      target_x = r->state.pose.x;
      target_y = r->state.pose.y;
    }
  }
  auto send = [&](GoalMode mode) {
    const uint64_t id =
        sink.send(GoalCommand{state.selected_robot, mode, {target_x, target_y}, state.square_size, state.square_centred});
    state.status_line = std::string(id ? "" : "NOT sent: ") + goal_mode_name(mode) + " goal for " + state.selected_robot;
  };
  if (ImGui::Button("drive there (direct)")) send(GoalMode::Direct);
  ImGui::SameLine();
  if (ImGui::Button("drive there (planned)")) send(GoalMode::Planned);

  section_title("Square");
  ImGui::InputDouble("side m", &state.square_size, 0.1, 0.5, "%.2f");
  if (state.square_size < 0.1) state.square_size = 0.1;
  int anchor = state.square_centred ? 1 : 0;
  ImGui::RadioButton("target is a corner (+x, +y)", &anchor, 0);
  ImGui::SameLine();
  ImGui::RadioButton("target is the centre", &anchor, 1);
  state.square_centred = anchor == 1;
  if (ImGui::Button("drive the square")) send(GoalMode::Square);

  section_title("Hold");
  if (ImGui::Button("stop")) send(GoalMode::Stop);
  ImGui::SameLine();
  if (ImGui::Button("home")) send(GoalMode::Home);
  ImGui::SameLine();
  if (ImGui::Button("explore")) send(GoalMode::Explore);
  ImGui::SameLine();
  if (ImGui::Button("idle")) send(GoalMode::Idle);
  hint("Clicks with 'set target' use the square settings in square mode.");
}

}  // namespace slam::viewer

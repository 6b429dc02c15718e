// Manual drive tab (the 2019 calibration drive): a manual target, a square path of a given size
// with the target as its first corner or its centre, and a button per corner of that square, for
// the selected robot or every robot. The goals come from drive_goals.hpp; this file only lays
// out the widgets.
#include <imgui.h>

#include <array>
#include <cstdio>

#include "viewer/core/drive_goals.hpp"
#include "viewer/ui/panels.hpp"

namespace slam::viewer {
namespace {

void send(ViewerState& state, CommandSink& sink, const GoalCommand& goal) {
  state.status_line = (sink.send(goal) ? "" : "NOT sent: ") + describe(goal);
}

// The corner buttons laid out as the square lies on an unrotated map: corners 4 and 3 above,
// 1 and 2 below (driving order 1 → 2 → 3 → 4 → 1, anticlockwise).
void corner_buttons(ViewerState& state, CommandSink& sink, const DriveSettings& drive, bool planned) {
  const std::array<GoalCommand, 4> goals = corner_goals(drive, planned);
  const float width = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) / 2.0f;
  for (size_t i : {size_t{3}, size_t{2}, size_t{0}, size_t{1}}) {
    char label[64];
    std::snprintf(label, sizeof label, "corner %zu  (%.2f, %.2f)", i + 1, goals[i].target.x,
                  goals[i].target.y);
    if (ImGui::Button(label, ImVec2(width, 0.0f))) send(state, sink, goals[i]);
    if (i == 3 || i == 0) ImGui::SameLine();
  }
}

}  // namespace

void DrivePanel::draw(ViewerState& state, CommandSink& sink) {
  robot_selector(state, "robot");
  hint("Every button below drives %s.",
       state.selected_robot == "*" ? "every robot" : ("robot " + state.selected_robot).c_str());
  section_title("Target (map frame, metres)");
  ImGui::InputDouble("x", &target_x, 0.1, 1.0, "%.2f");
  ImGui::InputDouble("y", &target_y, 0.1, 1.0, "%.2f");
  if (ImGui::Button("use the selected robot's position")) {
    if (RobotView* r = state.robots.find(state.selected_robot); r && r->has_state) {
      target_x = r->state.pose.x;
      target_y = r->state.pose.y;
    }
  }
  // The settings as edited so far this frame.
  auto drive = [&] {
    return DriveSettings{state.selected_robot, {target_x, target_y}, state.square_size, state.square_centred};
  };
  if (ImGui::Button("drive there (direct)")) send(state, sink, drive_goal(drive(), GoalMode::Direct));
  ImGui::SameLine();
  if (ImGui::Button("drive there (planned)")) send(state, sink, drive_goal(drive(), GoalMode::Planned));

  section_title("Square");
  ImGui::InputDouble("side m", &state.square_size, 0.1, 0.5, "%.2f");
  if (state.square_size < 0.1) state.square_size = 0.1;
  int anchor = state.square_centred ? 1 : 0;
  ImGui::RadioButton("target = first corner (+x, +y)", &anchor, 0);
  ImGui::SameLine();
  ImGui::RadioButton("target = centre", &anchor, 1);
  state.square_centred = anchor == 1;
  if (ImGui::Button("drive the square")) send(state, sink, drive_goal(drive(), GoalMode::Square));
  ImGui::TextUnformatted("drive to one corner:");
  ImGui::SameLine();
  ImGui::RadioButton("direct", &corner_mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("planned", &corner_mode, 1);
  corner_buttons(state, sink, drive(), corner_mode == 1);

  section_title("Hold");
  if (ImGui::Button("stop")) send(state, sink, drive_goal(drive(), GoalMode::Stop));
  ImGui::SameLine();
  if (ImGui::Button("home")) send(state, sink, drive_goal(drive(), GoalMode::Home));
  ImGui::SameLine();
  if (ImGui::Button("explore")) send(state, sink, drive_goal(drive(), GoalMode::Explore));
  ImGui::SameLine();
  if (ImGui::Button("idle")) send(state, sink, drive_goal(drive(), GoalMode::Idle));
  hint("Clicks with 'set target' use the square settings in square mode.");
}

}  // namespace slam::viewer

// Manual drive tab (the 2019 calibration drive): a manual target, a square path of a given size
// with the target as its first corner or its centre, and a button per corner of that square, for
// the selected robot or every robot; and the mission tool. The actions are DriveTab's
// (core/drive_tab.hpp) and the mission tool's (core/mission_tool.hpp, clicks_tab.hpp); this file
// only lays out the widgets.
#include <imgui.h>

#include <array>
#include <cstdio>

#include "viewer/core/clicks_tab.hpp"
#include "viewer/ui/panels.hpp"

namespace slam::viewer {
namespace {

// The corner buttons laid out as the square lies on an unrotated map: corners 4 and 3 above,
// 1 and 2 below (driving order 1 → 2 → 3 → 4 → 1, anticlockwise).
void corner_buttons(DriveTab& tab, ViewerState& state, CommandSink& sink) {
  const std::array<GoalCommand, 4> goals = corner_goals(tab.settings(state), tab.planned_corners);
  const float width = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) / 2.0f;
  for (size_t i : {size_t{3}, size_t{2}, size_t{0}, size_t{1}}) {
    char label[64];
    std::snprintf(label, sizeof label, "corner %zu  (%.2f, %.2f)", i + 1, goals[i].target.x,
                  goals[i].target.y);
    if (ImGui::Button(label, ImVec2(width, 0.0f))) tab.drive_corner(state, sink, i);
    if (i == 3 || i == 0) ImGui::SameLine();
  }
}

// The mission tool: armed, left clicks on the map add waypoints; sent to the selected robot.
void mission_section(ViewerState& state, CommandSink& sink) {
  section_title("Mission (waypoints in order)");
  MissionTool& tool = state.mission_tool;
  bool armed = tool.armed();
  if (ImGui::Checkbox("add waypoints by left click", &armed)) tool.set_armed(armed);
  bool loop = tool.loop();
  if (ImGui::Checkbox("loop (patrol)", &loop)) tool.set_loop(loop);
  ImGui::Text("%zu waypoint(s)", tool.waypoints().size());
  if (ImGui::Button("send mission")) send_mission(state, sink);
  ImGui::SameLine();
  if (ImGui::Button("undo last")) tool.undo();
  ImGui::SameLine();
  if (ImGui::Button("clear")) tool.clear();
  if (state.selected_robot != "*")
    if (const RobotView* r = state.robots.find(state.selected_robot); r != nullptr && r->has_mission) {
      const msg::Mission& m = r->mission;
      ImGui::Text("mission %llu: %s, waypoint %u/%zu, %u lap(s)",
                  static_cast<unsigned long long>(m.mission_id), mission_status_name(m.status), m.current + 1,
                  m.waypoints.size(), m.laps);
      if (!m.reason.empty()) hint("%s", m.reason.c_str());
    }
  hint("A mission replaces the robot's goal; any goal sent later (stop, explore, a click) cancels it.");
}

}  // namespace

void draw_drive_tab(DriveTab& tab, ViewerState& state, CommandSink& sink) {
  robot_selector(state, "robot");
  hint("Every button below drives %s.",
       state.selected_robot == "*" ? "every robot" : ("robot " + state.selected_robot).c_str());
  section_title("Target (map frame, metres)");
  ImGui::InputDouble("x", &tab.target.x, 0.1, 1.0, "%.2f");
  ImGui::InputDouble("y", &tab.target.y, 0.1, 1.0, "%.2f");
  if (ImGui::Button("use the selected robot's position")) tab.use_robot_position(state);
  if (ImGui::Button("drive there (direct)")) tab.drive(state, sink, GoalMode::Direct);
  ImGui::SameLine();
  if (ImGui::Button("drive there (planned)")) tab.drive(state, sink, GoalMode::Planned);

  section_title("Square");
  double side = state.square_size;
  if (ImGui::InputDouble("side m", &side, 0.1, 0.5, "%.2f")) DriveTab::set_square_side(state, side);
  int anchor = state.square_centred ? 1 : 0;
  ImGui::RadioButton("target = first corner (+x, +y)", &anchor, 0);
  ImGui::SameLine();
  ImGui::RadioButton("target = centre", &anchor, 1);
  DriveTab::set_square_centred(state, anchor == 1);
  if (ImGui::Button("drive the square")) tab.drive(state, sink, GoalMode::Square);
  ImGui::TextUnformatted("drive to one corner:");
  int corner_mode = tab.planned_corners ? 1 : 0;
  ImGui::SameLine();
  ImGui::RadioButton("direct", &corner_mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("planned", &corner_mode, 1);
  tab.planned_corners = corner_mode == 1;
  corner_buttons(tab, state, sink);

  section_title("Hold");
  if (ImGui::Button("stop")) tab.drive(state, sink, GoalMode::Stop);
  ImGui::SameLine();
  if (ImGui::Button("home")) tab.drive(state, sink, GoalMode::Home);
  ImGui::SameLine();
  if (ImGui::Button("explore")) tab.drive(state, sink, GoalMode::Explore);
  ImGui::SameLine();
  if (ImGui::Button("idle")) tab.drive(state, sink, GoalMode::Idle);
  error_line(tab.error);
  hint("Clicks with 'set target' use the square settings in square mode.");
  mission_section(state, sink);
}

}  // namespace slam::viewer

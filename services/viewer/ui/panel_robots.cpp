// Robots tab: the default goal mode for every robot, the pose tool, and per robot its display
// settings, its own goal, a reset of its observations, its correction and its counters.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <cmath>

#include "viewer/core/clicks_tab.hpp"
#include "viewer/ui/panels.hpp"

namespace slam::viewer {
namespace {

bool mode_combo(const char* label, GoalMode* mode) {
  const auto& modes = msg::kGoalModeNames;
  int m = static_cast<int>(*mode);
  if (!ImGui::Combo(label, &m, modes.data(), static_cast<int>(modes.size()))) return false;
  *mode = static_cast<GoalMode>(m);
  return true;
}

void robot_details(RobotsTab& tab, ViewerState& state, CommandSink& sink, RobotView& r) {
  RobotSettings& s = r.settings;
  ImGui::ColorEdit4("colour", &s.color.r, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_AlphaBar);
  ImGui::SameLine();
  ImGui::Checkbox("visible", &s.visible);
  ImGui::SameLine();
  ImGui::Checkbox("path", &s.show_path);
  ImGui::SliderFloat("point radius px", &s.point_radius_px, 0.5f, 8.0f, "%.1f");
  ImGui::SliderFloat("size m", &s.size_m, 0.05f, 2.0f, "%.2f");
  int last_n = static_cast<int>(s.last_n);
  if (ImGui::InputInt("last N points (0 all)", &last_n, 100, 1000)) RobotsTab::set_last_n(s, last_n);

  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.45f);  // room for the buttons beside it
  mode_combo("mode", &s.mode);
  ImGui::SameLine();
  if (ImGui::SmallButton("send")) tab.send_robot_mode(state, sink, r);
  ImGui::SameLine();
  if (ImGui::SmallButton("select")) RobotsTab::select(state, r.id);
  if (ImGui::Button("reset robot (delete its observations)")) tab.reset_robot(state, sink, r);
  ImGui::SameLine();
  // Gateways, planners and viewers drop it (goal, path, alerts); its map data stays.
  if (ImGui::Button("forget")) tab.forget_robot(state, sink, r);

  if (r.has_state) {
    const msg::RobotState& st = r.state;
    ImGui::Text("%s %s  pose (%.2f, %.2f, %.0f deg)%s", st.protocol_v2 ? "v2" : "v1",
                st.online ? "online" : "OFFLINE", st.pose.x, st.pose.y, st.pose.theta * 180.0 / M_PI,
                st.has_heading ? "" : " no heading");
    ImGui::Text("messages %llu  points %llu  rejected %llu", static_cast<unsigned long long>(st.messages),
                static_cast<unsigned long long>(st.points), static_cast<unsigned long long>(st.rejected));
    if (st.battery >= 0.0f) ImGui::Text("battery %.0f %%  status %s", st.battery * 100.0f, st.status.c_str());
  }
  if (r.has_correction) {
    const msg::PoseCorrection& c = r.correction;
    ImGui::Text("correction (%.3f, %.3f, %.2f deg) ±%.0f cm v%llu", c.map_from_odom.x, c.map_from_odom.y,
                c.map_from_odom.theta * 180.0 / M_PI, position_sigma(c.covariance) * 100.0,
                static_cast<unsigned long long>(c.version));
    ImGui::Text("  keyframes %u  loop closures %u  source %s", c.keyframes, c.loop_closures,
                correction_source_name(c.source));
    if (c.placement != msg::RobotPlacement::Placed)
      ImGui::Text("  %s on the map (score %.2f): not drawn yet", msg::robot_placement_name(c.placement),
                  c.localisation_score);
    // The operator's say on where it was found (slamctl placement accept|reject).
    if (c.placement == msg::RobotPlacement::Placing) {
      if (ImGui::SmallButton("accept placement")) tab.answer_placement(state, sink, r, true);
      ImGui::SameLine();
    }
    if (c.placement == msg::RobotPlacement::Placing || c.placement == msg::RobotPlacement::Placed) {
      if (ImGui::SmallButton("reject placement")) tab.answer_placement(state, sink, r, false);
    }
  } else {
    ImGui::TextDisabled("correction: none yet (identity)");
  }
  ImGui::Text("here: %llu observations, %zu points stored, %llu dropped",
              static_cast<unsigned long long>(r.observations), r.points.size(),
              static_cast<unsigned long long>(r.points.dropped()));
  if (r.has_path)
    ImGui::Text("goal %s %s, waypoint %u/%zu %s", goal_mode_name(r.path.mode),
                goal_status_name(r.path.status), r.path.current, r.path.waypoints.size(),
                r.path.reason.c_str());
}

}  // namespace

void draw_robots_tab(RobotsTab& tab, ViewerState& state, CommandSink& sink) {
  section_title("Every robot");
  RobotSettings& d = state.robots.defaults();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.45f);  // room for the button beside it
  mode_combo("default mode", &d.mode);
  ImGui::SameLine();
  if (ImGui::Button("send to all")) tab.send_default_mode(state, sink);
  ImGui::SliderFloat("default point radius", &d.point_radius_px, 0.5f, 8.0f, "%.1f");
  ImGui::SliderFloat("default size m", &d.size_m, 0.05f, 2.0f, "%.2f");
  ImGui::SliderFloat("default alpha", &d.color.a, 0.05f, 1.0f, "%.2f");
  int last_n = static_cast<int>(d.last_n);
  if (ImGui::InputInt("default last N", &last_n, 100, 1000)) RobotsTab::set_last_n(d, last_n);
  if (ImGui::Button("apply defaults to every robot")) RobotsTab::apply_defaults(state);
  robot_selector(state, "goals go to");
  error_line(tab.error);
  if (state.pose_tool.armed()) {
    ImGui::Text("setting the pose of %s: drag on the map", state.pose_tool.robot_id().c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("cancel")) cancel_pose_tool(state);
  } else if (ImGui::Button("set pose of the selected robot (drag on the map)")) {
    arm_pose_tool(state);
  }
  request_line(state.pose_requests);

  section_title("Robots");
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::InputTextWithHint("##robot-filter", "filter by id...", &tab.filter);
  if (state.robots.size() == 0) ImGui::TextDisabled("no robot seen yet");
  for (size_t i = 0; i < state.robots.size(); ++i) {
    RobotView& r = state.robots.at(i);
    if (!tab.shows(r)) continue;
    ImGui::PushID(r.id.c_str());
    ImGui::ColorButton("##c", ImVec4(r.settings.color.r, r.settings.color.g, r.settings.color.b, 1.0f),
                       ImGuiColorEditFlags_NoTooltip, ImVec2(14, 14));
    ImGui::SameLine();
    if (ImGui::TreeNode("robot", "%s  %s  %zu pts", r.id.c_str(),
                        r.has_state && r.state.online ? "online" : "offline", r.points.size())) {
      robot_details(tab, state, sink, r);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void robot_selector(ViewerState& state, const char* label) {
  const char* shown = state.selected_robot == "*" ? "every robot" : state.selected_robot.c_str();
  if (ImGui::BeginCombo(label, shown)) {
    if (ImGui::Selectable("every robot", state.selected_robot == "*")) RobotsTab::select(state, "*");
    for (size_t i = 0; i < state.robots.size(); ++i) {
      const std::string& id = state.robots.at(i).id;
      if (ImGui::Selectable(id.c_str(), state.selected_robot == id)) RobotsTab::select(state, id);
    }
    ImGui::EndCombo();
  }
}

}  // namespace slam::viewer

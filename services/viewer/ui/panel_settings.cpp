// The smaller tabs (Clicks, Grid, Simulation, Map) and the panel window holding every tab.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdarg>

#include "viewer/core/clicks_tab.hpp"
#include "viewer/ui/panels.hpp"

namespace slam::viewer {
namespace {

bool action_combo(const char* label, ClickAction* a) {
  int v = static_cast<int>(*a);
  if (!ImGui::Combo(label, &v, kClickActionNames, IM_ARRAYSIZE(kClickActionNames))) return false;
  *a = static_cast<ClickAction>(v);
  return true;
}

void color_edit(const char* label, Rgba* c) {
  ImGui::ColorEdit3(label, &c->r, ImGuiColorEditFlags_NoInputs);
}

const ImVec4 kOkColor{0.5f, 0.9f, 0.5f, 1.0f};
const ImVec4 kFailedColor{1.0f, 0.45f, 0.45f, 1.0f};

}  // namespace

void section_title(const char* label) {
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextDisabled("%s", label);
}

void draw_clicks_tab(ViewerState& state) {
  ClickAction left = state.left_click;
  if (action_combo("left click", &left)) set_click_action(state, MouseButton::Left, left);
  ClickAction right = state.right_click;
  if (action_combo("right click", &right)) set_click_action(state, MouseButton::Right, right);
  robot_selector(state, "targets go to");
  hint(
      "Right or middle drag pans; wheel zooms about the cursor; Shift+wheel or Q/E rotate; V flips the "
      "vertical "
      "axis; F fits the map.");
}

void hint(const char* fmt, ...) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  va_list args;
  va_start(args, fmt);
  ImGui::TextWrappedV(fmt, args);
  va_end(args);
  ImGui::PopStyleColor();
}

void error_line(const std::string& error) {
  if (error.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, kFailedColor);
  ImGui::TextWrapped("%s", error.c_str());
  ImGui::PopStyleColor();
}

void request_line(const RequestTracker& requests) {
  if (!requests.last()) return;
  const RequestOutcome& r = *requests.last();
  const ImVec4 colour = r.state == RequestState::Ok        ? kOkColor
                        : r.state == RequestState::Waiting ? ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled)
                                                           : kFailedColor;
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  ImGui::TextWrapped("last request %s", describe(r).c_str());
  ImGui::PopStyleColor();
}

void draw_grid_tab(GridTab& tab, ViewerState& state, CommandSink& sink) {
  tab.adopt(state.grid);
  GridConfigCommand& request = tab.request;
  section_title("Mapper (sent as GridConfig)");
  ImGui::InputDouble("resolution m", &request.resolution, 0.01, 0.05, "%.3f");
  ImGui::InputDouble("origin x", &request.origin.x, 1.0, 5.0, "%.2f");
  ImGui::InputDouble("origin y", &request.origin.y, 1.0, 5.0, "%.2f");
  ImGui::InputDouble("width m", &request.width_m, 1.0, 10.0, "%.1f");
  ImGui::InputDouble("height m", &request.height_m, 1.0, 10.0, "%.1f");
  ImGui::InputDouble("inflation m", &request.inflation_radius, 0.05, 0.1, "%.2f");
  ImGui::Checkbox("legacy mode (2019: points obstruct, nothing cleared)", &request.legacy_mode);
  if (ImGui::Button("apply")) tab.apply(state, sink);
  ImGui::SameLine();
  if (ImGui::Button("clear manual obstructions")) tab.clear_obstructions(state, sink);
  error_line(tab.error);

  section_title("Display (this viewer only)");
  GridColors& c = state.grid_colors;
  ImGui::Checkbox("grid", &state.show_grid);
  ImGui::SameLine();
  ImGui::Checkbox("points", &state.show_points);
  ImGui::SameLine();
  ImGui::Checkbox("robots", &state.show_robots);
  ImGui::SameLine();
  ImGui::Checkbox("paths", &state.show_paths);
  ImGui::SameLine();
  ImGui::Checkbox("names", &state.show_names);
  ImGui::SliderFloat("map alpha", &c.alpha, 0.0f, 1.0f, "%.2f");
  color_edit("unknown", &c.unknown);
  ImGui::SameLine();
  color_edit("free", &c.free);
  ImGui::SameLine();
  color_edit("occupied", &c.occupied);
  color_edit("inflated", &c.inflated);
  ImGui::SameLine();
  color_edit("obstructed", &c.obstructed);
  ImGui::Checkbox("show inflation", &c.show_inflation);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(120.0f);
  ImGui::SliderFloat("mix", &c.inflation_mix, 0.0f, 1.0f, "%.2f");
}

void draw_sim_tab(SimTab& tab, ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (state.truth)
    ImGui::Text("simulator: %zu robots, %s", state.truth->robots.size(),
                state.truth->paused ? "paused" : "running");
  else
    ImGui::TextDisabled("no simulator ground truth seen");
  if (state.world)
    ImGui::Text("world %s (%.1f x %.1f m, %zu walls)", state.world->name.c_str(), state.world->width_m,
                state.world->height_m, state.world->walls.size());
  ImGui::Checkbox("show true poses", &state.show_truth);
  ImGui::SameLine();
  ImGui::Checkbox("show walls", &state.show_world);
  request_line(state.sim_requests);
  error_line(tab.error);

  section_title("Robots");
  ImGui::InputInt("count", &tab.count);
  if (ImGui::Button("spawn")) tab.spawn(state, sink, now_ns);
  ImGui::InputText("robot id", &tab.robot_id);
  if (ImGui::Button("remove")) tab.remove(state, sink, now_ns);
  if (ImGui::Button("pause")) tab.pause(state, sink, now_ns);
  ImGui::SameLine();
  if (ImGui::Button("resume")) tab.resume(state, sink, now_ns);

  section_title("World and noise");
  ImGui::InputText("world (name or file)", &tab.world);
  if (ImGui::Button("set world")) tab.set_world(state, sink, now_ns);
  ImGui::InputDouble("range noise sd m", &tab.range_noise_sd, 0.005, 0.01, "%.3f");
  const double lo = 0.0, hi = 1.0;
  ImGui::SliderScalar("dropout", ImGuiDataType_Double, &tab.dropout, &lo, &hi, "%.2f");
  ImGui::InputDouble("odometry drift", &tab.odometry_drift, 0.001, 0.01, "%.3f");
  if (ImGui::Button("set noise")) tab.set_noise(state, sink, now_ns);
  ImGui::InputDouble("speed factor", &tab.speed_factor, 0.5, 1.0, "%.1f");
  if (ImGui::Button("set speed")) tab.set_speed(state, sink, now_ns);
}

void draw_map_tab(MapTab& tab, ViewerState& state, CommandSink& sink) {
  ImGui::TextWrapped("ROS map_server format (PGM + YAML), on the mapper's file system.");
  ImGui::InputText("YAML path", &tab.path);
  if (ImGui::Button("export")) tab.export_map(state, sink);
  ImGui::SameLine();
  if (ImGui::Button("import")) tab.import_map(state, sink);
  error_line(tab.error);
  section_title("Replies");
  if (state.replies.empty()) ImGui::TextDisabled("none yet");
  for (const auto& r : state.replies)
    ImGui::TextColored(r.result == 0 ? kOkColor : kFailedColor, "#%llu %s %s",
                       static_cast<unsigned long long>(r.request_id), r.result == 0 ? "ok" : "failed",
                       r.message.c_str());
}

void ControlPanel::draw(ViewerState& state, CommandSink& sink, float width, float height, int64_t now_ns) {
  ImGui::SetNextWindowPos({0.0f, 0.0f});
  ImGui::SetNextWindowSize({width, height});
  ImGui::Begin("SLAM fleet", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  if (!state.status_line.empty()) ImGui::TextWrapped("%s", state.status_line.c_str());
  if (ImGui::BeginTabBar("tabs", ImGuiTabBarFlags_FittingPolicyResizeDown)) {
    constexpr const char* kTabs[] = {"Main", "MQTT", "Clicks", "Robots", "Drive", "Grid", "Sim", "Map"};
    for (int i = 0; i < 8; ++i) {
      const ImGuiTabItemFlags flags = open_tab == i ? ImGuiTabItemFlags_SetSelected : 0;
      if (!ImGui::BeginTabItem(kTabs[i], nullptr, flags)) continue;
      ImGui::BeginChild("tab");
      switch (i) {
        case 0:
          draw_main_tab(state, now_ns);
          break;
        case 1:
          draw_mqtt_tab(mqtt, state, sink, now_ns);
          break;
        case 2:
          draw_clicks_tab(state);
          break;
        case 3:
          draw_robots_tab(robots, state, sink);
          break;
        case 4:
          draw_drive_tab(drive, state, sink);
          break;
        case 5:
          draw_grid_tab(grid, state, sink);
          break;
        case 6:
          draw_sim_tab(sim, state, sink, now_ns);
          break;
        default:
          draw_map_tab(map, state, sink);
          break;
      }
      ImGui::EndChild();
      ImGui::EndTabItem();
    }
    open_tab = -1;
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace slam::viewer

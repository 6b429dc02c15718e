// The smaller tabs (Clicks, Grid, Simulation, Map) and the panel window holding every tab.
#include <imgui.h>

#include <algorithm>
#include <cstdarg>
#include <cstring>

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

}  // namespace

void section_title(const char* label) {
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextDisabled("%s", label);
}

void ClicksPanel::draw(ViewerState& state) {
  action_combo("left click", &state.left_click);
  action_combo("right click", &state.right_click);
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

void GridPanel::draw(ViewerState& state, CommandSink& sink) {
  if (!initialised && state.grid.has_grid()) {
    const auto& g = state.grid.info();
    request.resolution = g.resolution;
    request.origin = g.origin;
    request.width_m = g.width * g.resolution;
    request.height_m = g.height * g.resolution;
    request.inflation_radius = g.inflation_radius;
    initialised = true;
  }
  section_title("Mapper (sent as GridConfig)");
  ImGui::InputDouble("resolution m", &request.resolution, 0.01, 0.05, "%.3f");
  ImGui::InputDouble("origin x", &request.origin.x, 1.0, 5.0, "%.2f");
  ImGui::InputDouble("origin y", &request.origin.y, 1.0, 5.0, "%.2f");
  ImGui::InputDouble("width m", &request.width_m, 1.0, 10.0, "%.1f");
  ImGui::InputDouble("height m", &request.height_m, 1.0, 10.0, "%.1f");
  ImGui::InputDouble("inflation m", &request.inflation_radius, 0.05, 0.1, "%.2f");
  ImGui::Checkbox("legacy mode (2019: points obstruct, nothing cleared)", &request.legacy_mode);
  if (ImGui::Button("apply")) {
    if (!(request.resolution > 0.0) || !(request.width_m > 0.0) || !(request.height_m > 0.0) ||
        request.inflation_radius < 0.0) {
      state.status_line = "grid: resolution, width and height must be positive, inflation not negative";
    } else {
      state.status_line = sink.send(request) ? "grid config sent" : "grid config NOT sent";
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("clear manual obstructions"))
    state.status_line =
        sink.send(MapEditCommand{MapEditKind::ClearObstructions, {}, {}}) ? "clear sent" : "clear NOT sent";

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

void SimPanel::draw(ViewerState& state, CommandSink& sink) {
  auto send = [&](SimCommandKind kind, const char* what) {
    SimCommand c = command;
    c.kind = kind;
    c.world = world;
    c.robot_id = robot_id;
    state.status_line = std::string(sink.send(c) ? "" : "NOT sent: ") + what;
  };
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

  section_title("Robots");
  int count = static_cast<int>(command.count);
  if (ImGui::InputInt("count", &count)) command.count = static_cast<uint32_t>(std::clamp(count, 1, 1000));
  if (ImGui::Button("spawn")) send(SimCommandKind::Spawn, "spawn");
  ImGui::InputText("robot id", robot_id, sizeof robot_id);
  if (ImGui::Button("remove") && robot_id[0] != '\0') send(SimCommandKind::Remove, "remove");
  if (ImGui::Button("pause")) send(SimCommandKind::Pause, "pause");
  ImGui::SameLine();
  if (ImGui::Button("resume")) send(SimCommandKind::Resume, "resume");

  section_title("World and noise");
  ImGui::InputText("world (name or file)", world, sizeof world);
  if (ImGui::Button("set world")) send(SimCommandKind::SetWorld, "set world");
  ImGui::InputDouble("range noise sd m", &command.range_noise_sd, 0.005, 0.01, "%.3f");
  const double lo = 0.0, hi = 1.0;
  ImGui::SliderScalar("dropout", ImGuiDataType_Double, &command.dropout, &lo, &hi, "%.2f");
  ImGui::InputDouble("odometry drift", &command.odometry_drift, 0.001, 0.01, "%.3f");
  if (ImGui::Button("set noise")) send(SimCommandKind::SetNoise, "set noise");
  ImGui::InputDouble("speed factor", &command.speed_factor, 0.5, 1.0, "%.1f");
  if (ImGui::Button("set speed")) send(SimCommandKind::SetSpeed, "set speed");
}

void MapPanel::draw(ViewerState& state, CommandSink& sink) {
  ImGui::TextWrapped("ROS map_server format (PGM + YAML), on the mapper's file system.");
  ImGui::InputText("YAML path", path, sizeof path);
  const bool ok = std::strlen(path) > 0;
  if (ImGui::Button("export") && ok)
    state.status_line = sink.send(MapFileCommand{false, path}) ? "export requested" : "export NOT sent";
  ImGui::SameLine();
  if (ImGui::Button("import") && ok)
    state.status_line = sink.send(MapFileCommand{true, path}) ? "import requested" : "import NOT sent";
  section_title("Replies");
  if (state.replies.empty()) ImGui::TextDisabled("none yet");
  for (const auto& r : state.replies)
    ImGui::TextColored(r.result == 0 ? ImVec4(0.5f, 0.9f, 0.5f, 1) : ImVec4(1, 0.5f, 0.5f, 1), "#%llu %s %s",
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
          main.draw(state, now_ns);
          break;
        case 1:
          mqtt.draw(state, sink);
          break;
        case 2:
          clicks.draw(state);
          break;
        case 3:
          robots.draw(state, sink);
          break;
        case 4:
          drive.draw(state, sink);
          break;
        case 5:
          grid.draw(state, sink);
          break;
        case 6:
          sim.draw(state, sink);
          break;
        default:
          map.draw(state, sink);
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

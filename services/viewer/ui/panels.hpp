#pragma once
// The control panel: one ImGui tab per job. What a control does lives in core/*_tab.hpp (plain
// structs with the tab's inputs and its actions, unit-tested without ImGui); the draw functions
// here only lay out widgets bound to those inputs and call the actions. Received data lives in
// ViewerState and is fed by ViewerState::ingest(), never by drawing. Commands leave through the
// CommandSink.
#include <imgui.h>

#include <cstdint>

#include "viewer/core/commands.hpp"
#include "viewer/core/drive_tab.hpp"
#include "viewer/core/grid_tab.hpp"
#include "viewer/core/map_tab.hpp"
#include "viewer/core/mqtt_tab.hpp"
#include "viewer/core/robots_tab.hpp"
#include "viewer/core/sim_tab.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

// The panel window (left of the map): every tab's inputs in one struct.
struct ControlPanel {
  MqttTab mqtt;
  RobotsTab robots;
  DriveTab drive;
  GridTab grid;
  SimTab sim;
  MapTab map;
  int open_tab = -1;  // select this tab once (0 = Main ... 7 = Map); for screenshots
  void draw(ViewerState& state, CommandSink& sink, float width, float height, int64_t now_ns);
};

void draw_main_tab(const ViewerState& state, int64_t now_ns);
void draw_mqtt_tab(MqttTab& tab, ViewerState& state, CommandSink& sink, int64_t now_ns);
void draw_clicks_tab(ViewerState& state);
void draw_robots_tab(RobotsTab& tab, ViewerState& state, CommandSink& sink);
void draw_drive_tab(DriveTab& tab, ViewerState& state, CommandSink& sink);
void draw_grid_tab(GridTab& tab, ViewerState& state, CommandSink& sink);
void draw_sim_tab(SimTab& tab, ViewerState& state, CommandSink& sink, int64_t now_ns);
void draw_map_tab(MapTab& tab, ViewerState& state, CommandSink& sink);

// Shared widgets: a separator with a title (ImGui 1.86 has no SeparatorText), a dimmed hint that
// wraps at the panel's edge instead of running out of it, a tab's refused input in red, the last
// tracked request's result, and a robot selector ("*" = every robot) bound to
// state.selected_robot.
void section_title(const char* label);
void hint(const char* fmt, ...) IM_FMTARGS(1);
void error_line(const std::string& error);
void request_line(const RequestTracker& requests);
void robot_selector(ViewerState& state, const char* label);

}  // namespace slam::viewer

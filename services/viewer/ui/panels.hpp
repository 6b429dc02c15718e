#pragma once
// The control panel: one ImGui tab per job. Each panel is a struct holding only its own UI state
// (text fields, toggles); received data lives in ViewerState and is fed by ViewerState::ingest(),
// never by Draw(). Commands leave through the CommandSink.
#include <imgui.h>

#include <cstdint>

#include "viewer/core/commands.hpp"
#include "viewer/ui/viewer_state.hpp"

namespace slam::viewer {

struct MainPanel {
  void draw(const ViewerState& state, int64_t now_ns);
};

struct MqttPanel {
  char filter[256] = "v1/robot/+/adv";
  char topic[256] = "v1/server/robot1/cmd";
  char payload[4096] = "";
  int payload_kind = 0;  // 0 SLAM v1 pairs, 1 raw hex, 2 text
  int qos = 0;
  bool retain = false;
  bool autoscroll = true;
  bool decoded = true;
  bool show_inbound = true;
  bool show_outbound = true;
  char search[128] = "";
  std::string error;
  void draw(ViewerState& state, CommandSink& sink);

 private:
  void draw_subscriptions(ViewerState& state, CommandSink& sink);
  void draw_publish(ViewerState& state, CommandSink& sink);
  void draw_log(ViewerState& state);
};

struct ClicksPanel {
  void draw(ViewerState& state);
};

struct RobotsPanel {
  char robot_filter[64] = "";
  void draw(ViewerState& state, CommandSink& sink);
};

struct DrivePanel {
  double target_x = 0.0;
  double target_y = 0.0;
  int corner_mode = 0;  // corner buttons send 0 direct, 1 planned goals
  void draw(ViewerState& state, CommandSink& sink);
};

struct GridPanel {
  GridConfigCommand request;
  bool initialised = false;  // request starts from the first grid seen
  void draw(ViewerState& state, CommandSink& sink);
};

struct SimPanel {
  SimCommand command;
  char world[1024] = "office";
  char robot_id[64] = "";
  void draw(ViewerState& state, CommandSink& sink);
};

struct MapPanel {
  char path[1024] = "/tmp/slam-map.yaml";
  void draw(ViewerState& state, CommandSink& sink);
};

// The panel window (left of the map) with every tab.
struct ControlPanel {
  MainPanel main;
  MqttPanel mqtt;
  ClicksPanel clicks;
  RobotsPanel robots;
  DrivePanel drive;
  GridPanel grid;
  SimPanel sim;
  MapPanel map;
  int open_tab = -1;  // select this tab once (0 = Main ... 7 = Map); for screenshots
  void draw(ViewerState& state, CommandSink& sink, float width, float height, int64_t now_ns);
};

// Shared widgets: a separator with a title (ImGui 1.86 has no SeparatorText), a dimmed hint that
// wraps at the panel's edge instead of running out of it, and a robot selector ("*" = every
// robot) bound to state.selected_robot.
void section_title(const char* label);
void hint(const char* fmt, ...) IM_FMTARGS(1);

void robot_selector(ViewerState& state, const char* label);

}  // namespace slam::viewer

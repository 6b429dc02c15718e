#pragma once
// Everything the render thread owns, in one struct (no function statics, no globals): the data
// drained from the intake each frame, the view, and the operator's local choices. Panels read
// and edit it; only ingest() feeds it from the intake.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "viewer/core/alert_board.hpp"
#include "viewer/core/cell_colors.hpp"
#include "viewer/core/click_actions.hpp"
#include "viewer/core/grid_mirror.hpp"
#include "viewer/core/intake.hpp"
#include "viewer/core/mission_tool.hpp"
#include "viewer/core/mqtt_log.hpp"
#include "viewer/core/path_preview.hpp"
#include "viewer/core/pose_tool.hpp"
#include "viewer/core/rate_meter.hpp"
#include "viewer/core/request_tracker.hpp"
#include "viewer/core/robot_registry.hpp"
#include "viewer/core/service_health.hpp"

namespace slam::viewer {

struct MessageRates {
  RateMeter observations;
  RateMeter points;
  RateMeter patches;
  RateMeter mqtt_in;
  RateMeter mqtt_out;
  void tick(int64_t now_ns);
};

struct ViewerState {
  explicit ViewerState(size_t max_points_per_robot) : robots(max_points_per_robot) {}

  // Data from other services.
  GridMirror grid;
  RobotRegistry robots;
  MqttLog mqtt;
  MqttSubscriptionsData subscriptions;
  bool have_subscriptions = false;
  ServiceHealth services;
  AlertBoard alerts;
  MessageRates rates;
  std::optional<SimWorldData> world;
  std::optional<SimTruthData> truth;
  std::deque<MapReplyData> replies;  // newest first, a few kept
  RequestTracker mqtt_requests;      // the MQTT tab's last request and the gateway's reply
  RequestTracker sim_requests;       // the Sim tab's last command and the simulator's reply
  RequestTracker pose_requests;      // the pose tool's last InitialPose and the mapper's reply
  uint64_t snapshots = 0;
  uint64_t patches_dropped = 0;
  uint64_t mqtt_dropped = 0;
  std::string grid_error;

  // View and display choices.
  ViewTransform view;
  bool view_touched = false;  // the operator moved the view: stop fitting automatically
  GridColors grid_colors;
  bool show_grid = true;
  bool show_points = true;
  bool show_robots = true;
  bool show_paths = true;
  bool show_truth = true;
  bool show_world = true;
  bool show_names = true;

  // Operator choices that shape commands.
  ClickAction left_click = ClickAction::SetTarget;
  ClickAction right_click = ClickAction::Obstruct;
  std::string selected_robot = "*";  // goals and manual drive go here; "*" = every robot
  double square_size = 1.0;
  bool square_centred = false;
  PoseTool pose_tool;        // "Set pose": drag on the map sends the selected robot an InitialPose
  PathPreview path_preview;  // "Preview path": two clicks send a PathRequest, the reply is drawn
  MissionTool mission_tool;  // while armed, left clicks add waypoints to a mission for the selected robot

  // Process info.
  int64_t started_ns = 0;  // monotonic
  uint64_t frames = 0;
  double frame_ms = 0.0;
  std::string renderer;
  std::string status_line;  // last command result shown under the tabs

  // Moves one drained batch into the state (the only writer of received data); also declares
  // requests that waited too long unanswered.
  void ingest(IntakeBatch& batch, int64_t now_ns);
  // After a send: the status line names what was sent, or the tab's `error` says it was not
  // (the middleware refused the sample). Returns `id` (0: not sent).
  uint64_t note_sent(uint64_t id, const std::string& what, std::string& error);
  // The goal mode for `robot_id` ("*": the default mode).
  GoalMode mode_for(const std::string& robot_id);
};

}  // namespace slam::viewer

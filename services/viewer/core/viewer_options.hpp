#pragma once
// slam-viewer's settings: window size, headless screenshot run, periodic snapshots, test hooks
// (synthetic clicks), limits. A plain struct with defaults, its CLI11 binding and a validator naming the bad
// key.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "common/core/service_options.hpp"
#include "viewer/core/click_actions.hpp"
#include "viewer/core/point_pacer.hpp"

namespace slam::viewer {

// A synthetic click for tests: window pixel (x, y), button 0 = left, 1 = right, applied at
// `frame` (counted like --frames, from when the view is ready).
struct ClickSpec {
  double x = 0.0, y = 0.0;
  int button = 0;
  uint32_t frame = 0;
};

inline constexpr const char* kTabNames[] = {"main",  "mqtt", "clicks", "robots",
                                            "drive", "grid", "sim",    "map"};

// "X,Y,left|right@FRAME"
Result<ClickSpec> parse_click_spec(const std::string& text);

// A synthetic "Set pose" drag for tests: selects `robot`, presses at window pixel (x0, y0) and drags
// to (x1, y1) at frame `press`, releases there at frame `release` (frames as for --click).
struct PoseDragSpec {
  std::string robot;
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  uint32_t press = 0, release = 0;
};

// "ROBOT:X0,Y0>X1,Y1@PRESS-RELEASE"
Result<PoseDragSpec> parse_pose_drag_spec(const std::string& text);

struct ViewerOptions {
  ServiceOptions service;
  int width = 1280;
  int height = 800;
  std::string screenshot;  // headless: write this PNG after `frames` frames and exit
  uint32_t frames = 60;
  bool wait_map = false;       // headless: frames count only once a grid snapshot arrived ...
  uint32_t wait_robots = 0;    // ... and this many robots have points
  double max_wait_s = 30.0;    // give up (exit 1) when not ready by then
  double fps = 60.0;           // frame cap (Xvfb has no vsync)
  float panel_width = 420.0f;  // control panel on the left; the map takes the rest
  uint32_t max_points_per_robot = 16u << 20;
  uint32_t point_budget = 2'000'000;  // most points rasterised into the point texture in one frame
  double point_frame_ms = 60.0;       // frame time the point texture's re-render aims at
  std::string left_click = "target";
  std::string right_click = "obstruct";
  std::vector<std::string> click_texts;
  std::vector<std::string> pose_drag_texts;
  std::string tab;           // open this tab at start (main, mqtt, clicks, robots, drive, grid, sim, map)
  std::string snapshot_dir;  // keep running; every snapshot_period_s write DIR/snapshot-NNNN.png + latest.png
  double snapshot_period_s = 10.0;
  uint32_t snapshot_keep = 0;  // numbered snapshots kept (older ones deleted); 0 keeps all

  // Filled by validate():
  std::vector<ClickSpec> clicks;
  std::vector<PoseDragSpec> pose_drags;
  ClickAction left_action = ClickAction::SetTarget;
  ClickAction right_action = ClickAction::Obstruct;
  int tab_index = -1;
};

void add_viewer_options(CLI::App& app, ViewerOptions& o);
// Checks ranges and parses --click / --left-click / --right-click; the error names the flag.
Status validate(ViewerOptions& o);
// The point texture's step sizing from --point-budget and --point-frame-ms (valid once o is).
PacerConfig pacer_config(const ViewerOptions& o);

}  // namespace slam::viewer

#pragma once
// The render thread: window, Dear ImGui, the GL layers and the frame loop in ImGui's fixed order
// (poll → drain intake → new frame → panels and input → render → swap). Headless runs count
// frames once the awaited data arrived, apply synthetic clicks, write the PNG and stop. With
// --snapshot-dir the loop keeps running and reads the frame back once a period; a writer thread
// encodes and stores it.
#include <memory>
#include <optional>
#include <string>

#include "common/core/counters.hpp"
#include "viewer/core/auto_fit.hpp"
#include "viewer/core/commands.hpp"
#include "viewer/core/intake.hpp"
#include "viewer/core/snapshot_schedule.hpp"
#include "viewer/core/snapshot_writer.hpp"
#include "viewer/core/viewer_options.hpp"
#include "viewer/core/viewer_state.hpp"
#include "viewer/gl/gl_window.hpp"
#include "viewer/gl/grid_layer.hpp"
#include "viewer/gl/point_layer.hpp"
#include "viewer/ui/map_input.hpp"
#include "viewer/ui/panels.hpp"

namespace slam::viewer {

class ViewerApp {
 public:
  static Result<std::unique_ptr<ViewerApp>> create(const ViewerOptions& options, Intake& intake,
                                                   CommandSink& sink, Counters& counters);
  ~ViewerApp();
  ViewerApp(const ViewerApp&) = delete;
  ViewerApp& operator=(const ViewerApp&) = delete;

  // Runs until the window closes or shutdown is requested (exit code 0), or in headless mode
  // until the screenshot is written (0) or the awaited data never came (1).
  int run();

 private:
  ViewerApp(const ViewerOptions& options, Intake& intake, CommandSink& sink, Counters& counters);
  Status init_graphics();
  Status init_snapshots();
  void take_snapshot(int64_t now_ns);
  // One frame without the swap; `ready_frame` counts frames since the view became ready (or -1).
  void frame(int64_t now_ns, long ready_frame);
  void fit_automatically();
  void render_map(int fb_width, int fb_height, double fb_scale);
  bool ready() const;

  ViewerOptions options_;
  Intake& intake_;
  CommandSink& sink_;
  std::atomic<int64_t>& frames_counter_;
  std::unique_ptr<GlWindow> window_;
  bool imgui_ready_ = false;
  GridLayer grid_layer_;
  PointLayer point_layer_;
  ViewerState state_;
  ControlPanel panel_;
  MapInput input_;
  IntakeBatch batch_;
  AutoFit auto_fit_;
  std::optional<SnapshotSchedule> snapshot_schedule_;
  std::unique_ptr<SnapshotWriter> snapshot_writer_;
};

}  // namespace slam::viewer

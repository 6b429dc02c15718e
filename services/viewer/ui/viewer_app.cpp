// Window, ImGui and the frame loop (see viewer_app.hpp).
#include "viewer/ui/viewer_app.hpp"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "common/core/clock.hpp"
#include "common/core/shutdown.hpp"
#include "viewer/core/clicks_tab.hpp"
#include "viewer/ui/map_overlay.hpp"

namespace slam::viewer {

ViewerApp::ViewerApp(const ViewerOptions& options, Intake& intake, CommandSink& sink, Counters& counters)
    : options_(options),
      intake_(intake),
      sink_(sink),
      frames_counter_(counters.get("frames")),
      state_(options.max_points_per_robot) {
  state_.left_click = options.left_action;
  state_.right_click = options.right_action;
  state_.started_ns = monotonic_ns();
  panel_.open_tab = options.tab_index;
}

Result<std::unique_ptr<ViewerApp>> ViewerApp::create(const ViewerOptions& options, Intake& intake,
                                                     CommandSink& sink, Counters& counters) {
  std::unique_ptr<ViewerApp> app(new ViewerApp(options, intake, sink, counters));
  if (Status s = app->init_graphics(); !s) return s.error();
  if (Status s = app->init_snapshots(); !s) return s.error();
  return app;
}

Status ViewerApp::init_graphics() {
  auto w = GlWindow::create("SLAM fleet viewer", options_.width, options_.height);
  if (!w) return w.error();
  window_ = std::move(*w);
  state_.renderer = window_->renderer();
  spdlog::info("OpenGL renderer: {}", state_.renderer);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini: every start looks the same
  ImGui::StyleColorsDark();
  if (!ImGui_ImplGlfw_InitForOpenGL(window_->handle(), true) || !ImGui_ImplOpenGL3_Init("#version 330 core"))
    return Error{"cannot initialise the Dear ImGui GLFW/OpenGL3 backends"};
  imgui_ready_ = true;
  if (Status s = grid_layer_.init(); !s) return s;
  if (Status s = point_layer_.init(pacer_config(options_)); !s) return s;
  return {};
}

Status ViewerApp::init_snapshots() {
  if (options_.snapshot_dir.empty()) return {};
  auto first = prepare_snapshot_dir(options_.snapshot_dir);
  if (!first) return first.status();
  snapshot_schedule_.emplace(options_.snapshot_dir, options_.snapshot_period_s, *first,
                             options_.snapshot_keep);
  snapshot_writer_ = std::make_unique<SnapshotWriter>();
  spdlog::info("snapshots every {} s: {}/{} on, and {}/latest.png", options_.snapshot_period_s,
               options_.snapshot_dir, snapshot_file_name(*first), options_.snapshot_dir);
  return {};
}

void ViewerApp::take_snapshot(int64_t now_ns) {
  int fbw = 0, fbh = 0;
  window_->framebuffer_size(&fbw, &fbh);
  if (fbw <= 0 || fbh <= 0) {  // minimised: nothing to read; try again next period
    snapshot_schedule_->skip(now_ns);
    return;
  }
  SnapshotJob job;
  job.names = snapshot_schedule_->take(now_ns);
  const int64_t t0 = monotonic_ns();
  job.image = read_back_buffer(fbw, fbh);
  char read_ms[32];
  std::snprintf(read_ms, sizeof read_ms, "read back in %.1f ms, ",
                static_cast<double>(monotonic_ns() - t0) / 1e6);
  job.summary = read_ms + std::to_string(state_.robots.online()) + "/" +
                std::to_string(state_.robots.size()) + " robots online, " +
                std::to_string(state_.robots.total_points()) + " points, map " +
                (state_.grid.has_grid() ? std::to_string(state_.grid.info().width) + "x" +
                                              std::to_string(state_.grid.info().height) + " cells"
                                        : std::string("none yet"));
  const std::string path = job.names.path;
  if (!snapshot_writer_->submit(std::move(job)))
    spdlog::warn("snapshot {} skipped: the previous one is still being written", path);
}

ViewerApp::~ViewerApp() {
  if (imgui_ready_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
}

bool ViewerApp::ready() const {
  if (options_.wait_map && !state_.grid.has_grid()) return false;
  size_t with_points = 0;
  for (size_t i = 0; i < state_.robots.size(); ++i) with_points += state_.robots.at(i).points.empty() ? 0 : 1;
  return with_points >= options_.wait_robots;
}

void ViewerApp::fit_automatically() {
  const std::optional<WorldBox> content = content_box(state_);
  std::optional<WorldBox> grid;
  if (state_.grid.has_grid()) grid = state_.grid.bounds();
  const auto box =
      auto_fit_.update(content, grid, state_.grid.layout_id(), state_.view.viewport(), state_.view_touched);
  if (!box) return;
  state_.view.fit(*box);
  spdlog::info("fitted to the {}: {}", content ? "content" : "grid's extent", state_.view.describe());
}

void ViewerApp::render_map(int fb_width, int fb_height, double fb_scale) {
  glViewport(0, 0, fb_width, fb_height);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.12f, 0.13f, 0.15f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const PixelRect px = to_pixels(state_.view.viewport(), fb_scale, fb_height);
  set_gl_viewport(px);
  grid_layer_.sync(state_.grid);
  if (state_.show_grid) grid_layer_.draw(state_.view, state_.grid_colors, state_.grid);
  point_layer_.sync(state_.robots);
  if (state_.show_points) point_layer_.draw(state_.view, px, state_.robots, fb_scale);
  glViewport(0, 0, fb_width, fb_height);
}

void ViewerApp::frame(int64_t now_ns, long ready_frame) {
  int ww = 0, wh = 0, fbw = 0, fbh = 0;
  glfwGetWindowSize(window_->handle(), &ww, &wh);
  window_->framebuffer_size(&fbw, &fbh);
  const double panel = std::min<double>(options_.panel_width, ww - 64.0);
  state_.view.set_viewport({panel, 0.0, std::max(1.0, ww - panel), std::max(1.0, static_cast<double>(wh))});

  intake_.drain(batch_);
  state_.ingest(batch_, now_ns);
  fit_automatically();

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  if (panel > 0.0) panel_.draw(state_, sink_, static_cast<float>(panel), static_cast<float>(wh), now_ns);
  draw_view_bar(state_);
  input_.handle(state_, sink_, now_ns);
  for (const ClickSpec& c : options_.clicks)
    if (ready_frame == static_cast<long>(c.frame)) {
      apply_click(state_, sink_, {c.x, c.y}, c.button == 0 ? MouseButton::Left : MouseButton::Right);
      spdlog::info("synthetic {} click at ({}, {}): {}", c.button == 0 ? "left" : "right", c.x, c.y,
                   state_.status_line);
    }
  for (const PoseDragSpec& d : options_.pose_drags) {
    if (ready_frame == static_cast<long>(d.press)) {
      state_.selected_robot = d.robot;
      arm_pose_tool(state_);
      pose_press(state_, {d.x0, d.y0});
      pose_drag(state_, {d.x1, d.y1});
      spdlog::info("synthetic pose drag for {} from ({}, {}) to ({}, {})", d.robot, d.x0, d.y0, d.x1, d.y1);
    }
    if (ready_frame == static_cast<long>(d.release)) {
      pose_release(state_, sink_, {d.x1, d.y1}, now_ns);
      spdlog::info("synthetic pose release: {}", state_.status_line);
    }
  }
  draw_map_overlay(state_);
  ImGui::Render();

  render_map(fbw, fbh, window_->framebuffer_scale());
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  ++state_.frames;
  bump(frames_counter_);
}

int ViewerApp::run() {
  const bool headless = !options_.screenshot.empty();
  const auto period = std::chrono::duration<double>(1.0 / options_.fps);
  const int64_t started = monotonic_ns();
  long ready_frames = -1;
  if (snapshot_schedule_) snapshot_schedule_->start(started);
  while (!glfwWindowShouldClose(window_->handle()) && !shutdown_requested()) {
    const auto t0 = std::chrono::steady_clock::now();
    glfwPollEvents();
    const int64_t now = monotonic_ns();
    if (ready_frames < 0 && ready()) ready_frames = 0;
    if (headless && ready_frames < 0 && static_cast<double>(now - started) / 1e9 > options_.max_wait_s) {
      spdlog::error("not ready after {} s: map {}, {} robots known (waiting for {} with points)",
                    options_.max_wait_s, state_.grid.has_grid() ? "received" : "missing",
                    state_.robots.size(), options_.wait_robots);
      return 1;
    }
    frame(now, ready_frames);
    if (headless && ready_frames >= 0 && ++ready_frames >= static_cast<long>(options_.frames)) {
      int fbw = 0, fbh = 0;
      window_->framebuffer_size(&fbw, &fbh);
      if (Status s = write_screenshot(options_.screenshot, fbw, fbh); !s) {
        spdlog::error("{}", s.message());
        return 1;
      }
      spdlog::info("{}", state_.view.describe());
      spdlog::info("screenshot {} written ({}x{}, {} frames, {} points)", options_.screenshot, fbw, fbh,
                   state_.frames, state_.robots.total_points());
      return 0;
    }
    if (snapshot_schedule_ && snapshot_schedule_->due(monotonic_ns())) take_snapshot(monotonic_ns());
    glfwSwapBuffers(window_->handle());
    const auto spent = std::chrono::steady_clock::now() - t0;
    const double spent_ms = std::chrono::duration<double, std::milli>(spent).count();
    point_layer_.end_frame(spent_ms);
    state_.frame_ms = 0.9 * state_.frame_ms + 0.1 * spent_ms;
    if (spent < period) std::this_thread::sleep_for(period - spent);
  }
  return 0;
}

}  // namespace slam::viewer

// slam-viewer flags and their validation (see viewer_options.hpp).
#include "viewer/core/viewer_options.hpp"

#include <algorithm>
#include <cstdio>

namespace slam::viewer {

Result<ClickSpec> parse_click_spec(const std::string& text) {
  ClickSpec c;
  char button[16] = {};
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%15[a-z]@%u%n", &c.x, &c.y, button, &c.frame, &consumed) != 4 ||
      static_cast<size_t>(consumed) != text.size())
    return Error{"--click '" + text + "': expected X,Y,left|right@FRAME"};
  const std::string b = button;
  if (b == "left") {
    c.button = 0;
  } else if (b == "right") {
    c.button = 1;
  } else {
    return Error{"--click '" + text + "': button must be left or right"};
  }
  return c;
}

Result<PoseDragSpec> parse_pose_drag_spec(const std::string& text) {
  PoseDragSpec d;
  const auto colon = text.find(':');
  const std::string expected = "--pose-drag '" + text + "': expected ROBOT:X0,Y0>X1,Y1@PRESS-RELEASE";
  if (colon == std::string::npos || colon == 0) return Error{expected};
  d.robot = text.substr(0, colon);
  const std::string rest = text.substr(colon + 1);
  int consumed = 0;
  if (std::sscanf(rest.c_str(), "%lf,%lf>%lf,%lf@%u-%u%n", &d.x0, &d.y0, &d.x1, &d.y1, &d.press, &d.release,
                  &consumed) != 6 ||
      static_cast<size_t>(consumed) != rest.size())
    return Error{expected};
  if (d.release <= d.press) return Error{"--pose-drag '" + text + "': RELEASE must come after PRESS"};
  return d;
}

void add_viewer_options(CLI::App& app, ViewerOptions& o) {
  add_service_options(app, o.service);
  app.add_option("--width", o.width, "window width in pixels")->capture_default_str();
  app.add_option("--height", o.height, "window height in pixels")->capture_default_str();
  app.add_option("--screenshot", o.screenshot, "headless: write a PNG after --frames frames, then exit");
  app.add_option("--frames", o.frames, "frames to render before the screenshot")->capture_default_str();
  app.add_flag("--wait-map", o.wait_map, "with --screenshot: count frames only once a map arrived");
  app.add_option("--wait-robots", o.wait_robots, "with --screenshot: ... and this many robots sent points")
      ->capture_default_str();
  app.add_option("--max-wait", o.max_wait_s, "with --screenshot: seconds to wait for map/robots")
      ->capture_default_str();
  app.add_option("--fps", o.fps, "frame-rate cap")->capture_default_str();
  app.add_option("--panel-width", o.panel_width, "control panel width in pixels (0 hides it)")
      ->capture_default_str();
  app.add_option("--max-points", o.max_points_per_robot, "measurement points kept per robot")
      ->capture_default_str();
  app.add_option("--point-budget", o.point_budget, "most points drawn into the point texture in one frame")
      ->capture_default_str();
  app.add_option("--point-frame-ms", o.point_frame_ms,
                 "frame time in ms the point texture's re-render aims at (sizes its steps)")
      ->capture_default_str();
  app.add_option("--left-click", o.left_click, "left click: nothing|target|obstruct|unobstruct")
      ->capture_default_str();
  app.add_option("--right-click", o.right_click, "right click: nothing|target|obstruct|unobstruct")
      ->capture_default_str();
  app.add_option("--tab", o.tab, "open this tab at start: main|mqtt|clicks|robots|drive|grid|sim|map");
  app.add_option("--snapshot-dir", o.snapshot_dir,
                 "keep running and write DIR/snapshot-NNNN.png and DIR/latest.png every --snapshot-period");
  app.add_option("--snapshot-period", o.snapshot_period_s, "seconds between snapshots")
      ->capture_default_str();
  app.add_option("--snapshot-keep", o.snapshot_keep,
                 "numbered snapshots kept, older ones deleted (0 keeps all)")
      ->capture_default_str();
  app.add_option("--click", o.click_texts, "test hook: synthetic click X,Y,left|right@FRAME (repeatable)");
  app.add_option("--pose-drag", o.pose_drag_texts,
                 "test hook: synthetic Set pose drag ROBOT:X0,Y0>X1,Y1@PRESS-RELEASE (repeatable)");
}

Status validate(ViewerOptions& o) {
  if (o.width < 64 || o.width > 16384)
    return Error{"--width must be 64..16384, got " + std::to_string(o.width)};
  if (o.height < 64 || o.height > 16384)
    return Error{"--height must be 64..16384, got " + std::to_string(o.height)};
  if (!o.screenshot.empty() && o.frames == 0) return Error{"--frames must be at least 1 with --screenshot"};
  if (!(o.max_wait_s > 0.0)) return Error{"--max-wait must be positive"};
  if (!(o.fps >= 1.0 && o.fps <= 1000.0)) return Error{"--fps must be 1..1000"};
  if (o.panel_width < 0.0f || o.panel_width > static_cast<float>(o.width) - 64.0f)
    return Error{"--panel-width must be 0..(width - 64)"};
  if (o.max_points_per_robot == 0) return Error{"--max-points must be positive"};
  if (!(o.snapshot_period_s >= 0.1 && o.snapshot_period_s <= 86400.0))
    return Error{"--snapshot-period must be 0.1..86400 seconds"};
  if (!o.snapshot_dir.empty() && !o.screenshot.empty())
    return Error{"--snapshot-dir and --screenshot exclude each other (periodic snapshots vs one and exit)"};
  if (o.point_budget < 1000) return Error{"--point-budget must be at least 1000"};
  if (!(o.point_frame_ms >= 1.0 && o.point_frame_ms <= 1000.0))
    return Error{"--point-frame-ms must be 1..1000"};
  auto left = parse_click_action(o.left_click);
  if (!left) return Error{"--left-click: " + left.message()};
  auto right = parse_click_action(o.right_click);
  if (!right) return Error{"--right-click: " + right.message()};
  o.left_action = *left;
  o.right_action = *right;
  o.tab_index = -1;
  for (int i = 0; i < 8; ++i)
    if (o.tab == kTabNames[i]) o.tab_index = i;
  if (!o.tab.empty() && o.tab_index < 0) return Error{"--tab '" + o.tab + "' is not a tab name"};
  o.clicks.clear();
  for (const auto& t : o.click_texts) {
    auto c = parse_click_spec(t);
    if (!c) return c.status();
    o.clicks.push_back(*c);
  }
  o.pose_drags.clear();
  for (const auto& t : o.pose_drag_texts) {
    auto d = parse_pose_drag_spec(t);
    if (!d) return d.status();
    o.pose_drags.push_back(*d);
  }
  return {};
}

PacerConfig pacer_config(const ViewerOptions& o) {
  PacerConfig c;
  c.frame_ms = o.point_frame_ms;
  c.max_points = o.point_budget;
  c.min_points = std::min<uint64_t>(c.min_points, o.point_budget);
  c.first_points = std::min<uint64_t>(c.first_points, o.point_budget);
  return c;
}

}  // namespace slam::viewer

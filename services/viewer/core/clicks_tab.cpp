// Click settings and map clicks (see clicks_tab.hpp).
#include "viewer/core/clicks_tab.hpp"

#include <cmath>
#include <cstdio>

namespace slam::viewer {

void set_click_action(ViewerState& state, MouseButton button, ClickAction action) {
  (button == MouseButton::Left ? state.left_click : state.right_click) = action;
}

void apply_click(ViewerState& state, CommandSink& sink, Vec2 screen, MouseButton button) {
  if (button == MouseButton::Left && state.mission_tool.armed()) {
    add_mission_waypoint(state, screen);
    return;
  }
  const ClickAction action = button == MouseButton::Left ? state.left_click : state.right_click;
  const Vec2 w = state.view.screen_to_world(screen);
  const ClickOutcome out =
      click_outcome(action, w, state.selected_robot, state.mode_for(state.selected_robot), state.square_size,
                    state.square_centred);
  char where[64];
  std::snprintf(where, sizeof where, "(%.2f, %.2f)", w.x, w.y);
  // A click has no tab of its own to show a refusal in: both outcomes go to the status line.
  std::string error;
  if (out.goal) {
    const std::string what = "goal for " + state.selected_robot + " at " + where;
    if (!state.note_sent(sink.send(*out.goal), what, error)) state.status_line = error;
  }
  if (out.edit) {
    const std::string what = std::string(click_action_name(action)) + " at " + where;
    if (!state.note_sent(sink.send(*out.edit), what, error)) state.status_line = error;
  }
}

void arm_pose_tool(ViewerState& state) {
  if (Status s = state.pose_tool.arm(state.selected_robot); !s) {
    state.status_line = s.message();
    return;
  }
  state.status_line = "set pose of " + state.selected_robot +
                      ": press at its true position, drag towards its heading (Esc cancels)";
}

void pose_press(ViewerState& state, Vec2 screen) {
  state.pose_tool.press(state.view.screen_to_world(screen));
}

void pose_drag(ViewerState& state, Vec2 screen) {
  state.pose_tool.drag(state.view.screen_to_world(screen));
}

void pose_release(ViewerState& state, CommandSink& sink, Vec2 screen, int64_t now_ns) {
  const auto pose =
      state.pose_tool.release(state.view.screen_to_world(screen), kPoseMinDragPx / state.view.scale());
  if (!pose) {
    if (state.pose_tool.armed()) state.status_line = "set pose: drag towards the robot's heading";
    return;
  }
  char what[160];
  std::snprintf(what, sizeof what, "pose of %s: (%.2f, %.2f, %.0f deg)", pose->robot_id.c_str(), pose->pose.x,
                pose->pose.y, pose->pose.theta * 180.0 / M_PI);
  std::string error;
  if (const uint64_t id = state.note_sent(sink.send(*pose), what, error)) {
    state.pose_requests.sent(id, what, now_ns);
  } else {
    state.status_line = error;
  }
}

void add_mission_waypoint(ViewerState& state, Vec2 screen) {
  const Vec2 w = state.view.screen_to_world(screen);
  if (Status s = state.mission_tool.add(w); !s) {
    state.status_line = s.message();
    return;
  }
  char line[96];
  std::snprintf(line, sizeof line, "mission waypoint %zu at (%.2f, %.2f)",
                state.mission_tool.waypoints().size(), w.x, w.y);
  state.status_line = line;
}

void send_mission(ViewerState& state, CommandSink& sink) {
  auto mission = state.mission_tool.command(state.selected_robot);
  if (!mission) {
    state.status_line = mission.message();
    return;
  }
  const std::string what = "mission of " + std::to_string(mission->waypoints.size()) + " waypoint(s)" +
                           (mission->loop ? ", looped," : "") + " for " + mission->robot_id;
  std::string error;
  if (!state.note_sent(sink.send(*mission), what, error)) state.status_line = error;
}

void cancel_pose_tool(ViewerState& state) {
  if (!state.pose_tool.armed()) return;
  state.pose_tool.cancel();
  state.status_line = "set pose cancelled";
}

}  // namespace slam::viewer

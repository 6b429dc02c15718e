#pragma once
// The Clicks tab and clicks on the map without ImGui: which action each mouse button takes, the
// command a click at a window point sends (real clicks and --click share apply_click()), and the
// "Set pose" tool's press, drag and release at window points (real drags and --pose-drag share them).
#include "viewer/core/click_actions.hpp"
#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

enum class MouseButton : uint8_t { Left, Right };

void set_click_action(ViewerState& state, MouseButton button, ClickAction action);

// Sends what `button`'s action asks for at window point `screen` (nothing for "nothing") and
// names it on the status line. While the mission tool is armed, the left button adds a waypoint.
void apply_click(ViewerState& state, CommandSink& sink, Vec2 screen, MouseButton button);

// A drag shorter than this (window pixels) gives the pose tool no heading.
inline constexpr double kPoseMinDragPx = 6.0;

// Arms the pose tool for the selected robot; the status line says what to do next, or why not.
void arm_pose_tool(ViewerState& state);
void pose_press(ViewerState& state, Vec2 screen);
void pose_drag(ViewerState& state, Vec2 screen);
// Sends the InitialPose the drag describes (tracked in state.pose_requests until the mapper's
// MapReply); a too short drag sends nothing and keeps the tool armed.
void pose_release(ViewerState& state, CommandSink& sink, Vec2 screen, int64_t now_ns);
// Escape or a right click.
void cancel_pose_tool(ViewerState& state);

// The mission tool: a waypoint at window point `screen`, and sending the draft to the selected robot
// (the status line names what was sent, or why not).
void add_mission_waypoint(ViewerState& state, Vec2 screen);
void send_mission(ViewerState& state, CommandSink& sink);

}  // namespace slam::viewer

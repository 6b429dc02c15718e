#pragma once
// The Robots tab's controls without ImGui: the default goal mode sent to every robot, defaults
// applied to every robot, the id filter, and per robot its own goal, select and reset (delete its
// observations in the mapper, and the points stored here).
#include <string>

#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

struct RobotsTab {
  std::string filter;  // robot id contains
  std::string error;   // the last refused send, shown in red

  bool shows(const RobotView& r) const { return filter.empty() || r.id.find(filter) != std::string::npos; }
  // A goal in the default mode for every robot.
  void send_default_mode(ViewerState& state, CommandSink& sink);
  // A goal in the robot's own mode, to its current target (else its position).
  void send_robot_mode(ViewerState& state, CommandSink& sink, const RobotView& r);
  void reset_robot(ViewerState& state, CommandSink& sink, RobotView& r);
  // An operator's answer to where the mapper is placing the robot (or placed it: reject only).
  void answer_placement(ViewerState& state, CommandSink& sink, const RobotView& r, bool accept);
  // Gateways, planners and viewers (this one too, when its own command comes back) drop the robot.
  void forget_robot(ViewerState& state, CommandSink& sink, const RobotView& r);
  static void select(ViewerState& state, const std::string& robot_id) { state.selected_robot = robot_id; }
  static void apply_defaults(ViewerState& state) { state.robots.apply_defaults_to_all(); }
  // "last N points" from a typed number: negative means all (0).
  static void set_last_n(RobotSettings& s, int n) { s.last_n = n < 0 ? 0u : static_cast<uint32_t>(n); }
};

}  // namespace slam::viewer

// Click settings and map clicks (see clicks_tab.hpp).
#include "viewer/core/clicks_tab.hpp"

#include <cstdio>

namespace slam::viewer {

void set_click_action(ViewerState& state, MouseButton button, ClickAction action) {
  (button == MouseButton::Left ? state.left_click : state.right_click) = action;
}

void apply_click(ViewerState& state, CommandSink& sink, Vec2 screen, MouseButton button) {
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

}  // namespace slam::viewer

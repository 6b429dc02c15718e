#pragma once
// The Clicks tab and clicks on the map without ImGui: which action each mouse button takes, and
// the command a click at a window point sends (real clicks and --click share apply_click()).
#include "viewer/core/click_actions.hpp"
#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

enum class MouseButton : uint8_t { Left, Right };

void set_click_action(ViewerState& state, MouseButton button, ClickAction action);

// Sends what `button`'s action asks for at window point `screen` (nothing for "nothing") and
// names it on the status line.
void apply_click(ViewerState& state, CommandSink& sink, Vec2 screen, MouseButton button);

}  // namespace slam::viewer

#pragma once
// The "Preview path" tool at window points (real clicks and tests share these): arm it, a click
// for the start and one for the goal sends the PathRequest; the status line says what to do next.
#include <cstdint>

#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

void arm_path_preview(ViewerState& state);
void path_preview_click(ViewerState& state, CommandSink& sink, Vec2 screen, int64_t now_ns);
// Escape or a right click.
void cancel_path_preview(ViewerState& state);

}  // namespace slam::viewer

// Path preview clicks (see preview_clicks.hpp).
#include "viewer/core/preview_clicks.hpp"

#include <cstdio>

namespace slam::viewer {

void arm_path_preview(ViewerState& state) {
  state.path_preview.arm();
  state.status_line = "preview path: click the start, then the goal (Esc cancels)";
}

void path_preview_click(ViewerState& state, CommandSink& sink, Vec2 screen, int64_t now_ns) {
  const auto request = state.path_preview.click(state.view.screen_to_world(screen));
  if (!request) {
    state.status_line = "preview path: " + state.path_preview.summary();
    return;
  }
  char what[160];
  std::snprintf(what, sizeof what, "path preview (%.2f, %.2f) -> (%.2f, %.2f)", request->start.x,
                request->start.y, request->goal.x, request->goal.y);
  std::string error;
  const uint64_t id = state.note_sent(sink.send(*request), what, error);
  state.path_preview.sent(*request, id, now_ns);
  if (id == 0) state.status_line = error;
}

void cancel_path_preview(ViewerState& state) {
  if (!state.path_preview.armed()) return;
  state.path_preview.cancel();
  state.status_line = "preview path cancelled";
}

}  // namespace slam::viewer

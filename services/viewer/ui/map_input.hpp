#pragma once
// Mouse and keys over the map: pan (middle or right drag), zoom about the cursor (wheel), rotate
// (Shift+wheel, or Q/E), flip (V), fit (F), clicks that send what the Clicks tab chose, and the
// armed "Set pose" tool's left drag (Escape or a right click cancels it).
// Clicks go through apply_click() (core/clicks_tab.hpp), as synthetic clicks from --click do.
#include <optional>

#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

// What there is to see: the mapped (free or occupied) cells, every robot and point, and the
// simulated world's walls when they are shown; nothing before any of them arrived.
std::optional<WorldBox> content_box(const ViewerState& state);
// The box Fit (button or F) shows: the content, else the grid's extent; false when there is nothing.
bool fit_box(const ViewerState& state, WorldBox* box);

class MapInput {
 public:
  // Call once per frame after ImGui::NewFrame(), before the panels consume input.
  void handle(ViewerState& state, CommandSink& sink, int64_t now_ns);

 private:
  int drag_button_ = -1;  // 1 right, 2 middle; -1 none
  Vec2 press_{};
  Vec2 last_{};
  bool dragged_ = false;
  bool pose_drag_ = false;  // the pose tool's drag follows the mouse (not a --pose-drag hook)
};

}  // namespace slam::viewer

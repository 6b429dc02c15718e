#pragma once
// What is drawn over the map with ImGui's background draw list (few shapes, so no GL buffers):
// robots as oriented triangles with names, paths with waypoint markers and targets, the
// simulator's walls and true poses; and the small view bar (fit, flip, rotate, cursor position).
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

void draw_map_overlay(const ViewerState& state);

// The view bar at the top of the map; changes the view in `state`.
void draw_view_bar(ViewerState& state);

}  // namespace slam::viewer

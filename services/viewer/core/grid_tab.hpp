#pragma once
// The Grid tab's mapper controls without ImGui: the layout request (resolution, origin, extent,
// inflation, legacy mode) sent as GridConfig, and clearing manual obstructions. The request starts
// from the first grid seen; values the mapper would refuse set `error` and send nothing.
#include <string>

#include "common/core/result.hpp"
#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

// The mapper's own limits on a GridConfig that the viewer can check before sending.
Status validate(const GridConfigCommand& c);

struct GridTab {
  GridConfigCommand request;
  bool initialised = false;  // request was taken from the first grid seen
  std::string error;         // the last refused input, shown in red

  // Takes the first grid's layout into the request (later grids leave the operator's edits).
  void adopt(const GridMirror& grid);
  void apply(ViewerState& state, CommandSink& sink);
  void clear_obstructions(ViewerState& state, CommandSink& sink);
};

}  // namespace slam::viewer

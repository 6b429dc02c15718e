// Grid tab actions (see grid_tab.hpp).
#include "viewer/core/grid_tab.hpp"

#include <cmath>

namespace slam::viewer {
namespace {

bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

Status validate(const GridConfigCommand& c) {
  if (!positive(c.resolution) || c.resolution < 1e-3) return Error{"resolution must be at least 0.001 m"};
  if (!std::isfinite(c.origin.x) || !std::isfinite(c.origin.y) || std::abs(c.origin.x) > 1e6 ||
      std::abs(c.origin.y) > 1e6)
    return Error{"the origin must be finite, |x| and |y| at most 1e6 m"};
  if (!positive(c.width_m) || !positive(c.height_m)) return Error{"width and height must be positive"};
  if (!std::isfinite(c.inflation_radius) || c.inflation_radius < 0.0)
    return Error{"inflation must be finite and not negative"};
  return {};
}

void GridTab::adopt(const GridMirror& grid) {
  if (initialised || !grid.has_grid()) return;
  const msg::GridInfo& g = grid.info();
  request.resolution = g.resolution;
  request.origin = g.origin;
  request.width_m = g.width * g.resolution;
  request.height_m = g.height * g.resolution;
  request.inflation_radius = g.inflation_radius;
  initialised = true;
}

void GridTab::apply(ViewerState& state, CommandSink& sink) {
  if (Status s = validate(request); !s) {
    error = "grid: " + s.message();
    return;
  }
  state.note_sent(sink.send(request), "grid config", error);
}

void GridTab::clear_obstructions(ViewerState& state, CommandSink& sink) {
  state.note_sent(sink.send(MapEditCommand{MapEditKind::ClearObstructions, {}, {}}),
                  "clear manual obstructions", error);
}

}  // namespace slam::viewer

#pragma once
// When the view fits itself to the data, so a viewer started before the rest of the system (or
// running unattended under Xvfb, writing snapshots) shows the map and the robots without anyone
// pressing Fit. It fits the content (the mapped part of the grid and every robot and point, with
// some room to grow) and fits again when the content outgrows the fitted box, when the grid is
// re-laid out (it grew), and when the window changes size. Before anything is mapped it shows the
// grid's whole extent. Never once the operator moved the view. Pure logic, tested alone.
#include <cstdint>
#include <optional>

#include "viewer/core/view_transform.hpp"

namespace slam::viewer {

class AutoFit {
 public:
  // Content smaller than this (metres per side) is padded: one robot alone would otherwise be
  // zoomed in until it fills the window.
  static constexpr double kMinSide = 6.0;
  // Room left on each side of the content (a fraction of its size), so a map that grows as robots
  // explore re-fits the view now and then rather than at every patch.
  static constexpr double kSlack = 0.1;

  // The box to fit now, or nothing. `content`: the known cells and robots, when there are any;
  // `grid`: the grid's extent, when there is a grid, with its layout id.
  std::optional<WorldBox> update(const std::optional<WorldBox>& content, const std::optional<WorldBox>& grid,
                                 uint32_t layout_id, const Viewport& viewport, bool user_moved);

 private:
  enum class Basis { None, Extent, Content };
  Basis basis_ = Basis::None;
  uint32_t layout_id_ = 0;
  WorldBox fitted_;
  Viewport viewport_;
};

// The smallest box holding both.
WorldBox unite(const WorldBox& a, const WorldBox& b);

}  // namespace slam::viewer

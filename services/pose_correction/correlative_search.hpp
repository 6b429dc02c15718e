#pragma once
// The real-time correlative search of a scan match: every candidate of a lattice around a predicted
// pose (whole-cell x/y offsets, evenly spaced headings) scored by the summed likelihood of the points.
// Per heading the points are rotated once; every x/y offset is then one lookup per point.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "pose_correction/likelihood_field.hpp"

namespace slam::correction {

struct SearchWindow {
  double linear_m = 0.15;     // +- around the prediction in x and y
  double angular_rad = 0.08;  // +- around the predicted heading
};

// The candidates: index = (heading * side + iy) * side + ix.
struct SearchLattice {
  int32_t step_cells = 1;     // x/y step in whole cells
  double step_m = 0.0;        // the same in metres
  int32_t linear_steps = 0;   // steps either side in x and y
  int32_t angular_steps = 0;  // steps either side in heading
  double angular_step = 0.0;  // radians

  // `linear_step_m`, `angular_step_rad` 0: one cell, and the step that moves the farthest point
  // (`max_range`) by about one cell.
  static SearchLattice around(const SearchWindow& window, double resolution, double max_range,
                              double linear_step_m, double angular_step_rad);

  int32_t side() const { return 2 * linear_steps + 1; }
  int32_t headings() const { return 2 * angular_steps + 1; }
  size_t per_heading() const { return static_cast<size_t>(side()) * static_cast<size_t>(side()); }
  size_t size() const { return per_heading() * static_cast<size_t>(headings()); }
  // (dx, dy, dtheta) of a candidate from the prediction.
  Eigen::Vector3d offset(size_t index) const;
  // Whether an offset lies on the lattice's outer ring in x, y or heading.
  bool on_edge(const Eigen::Vector3d& offset) const;
};

class CorrelativeSearch {
 public:
  // The grid cells any candidate reads (the points swept by the window); an error when they lie off
  // the grid or beyond int32 cell indices.
  static Result<CellBox> cells_read(const GridGeometry& geometry, std::span<const Vec2> points,
                                    const Pose& predicted, const SearchWindow& window,
                                    const SearchLattice& lattice);

  // Scores every candidate against `field`, which must cover cells_read().
  void score(const LikelihoodField& field, const GridGeometry& geometry, std::span<const Vec2> points,
             const Pose& predicted, const SearchLattice& lattice);

  std::span<const float> sums() const { return sums_; }
  // The best candidate; among equals the one nearest the prediction, offsets compared after `scale`.
  size_t best(const SearchLattice& lattice, const Eigen::Vector3d& scale) const;

 private:
  // Reused between searches, so a search allocates nothing once they have grown to the largest window.
  std::vector<int32_t> lookup_;  // per point: field index of its cell at the current heading
  std::vector<float> sums_;      // per candidate
};

}  // namespace slam::correction

#include "pose_correction/scan_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pose_correction/field_refinement.hpp"
#include "pose_correction/response_spread.hpp"

namespace slam::correction {
namespace {

// Field cells kept around every lookup so bicubic interpolation near the edge reads real values.
constexpr int32_t kInterpolationMargin = 2;
// A keyframe whose search would need a larger field is refused rather than matched slowly.
constexpr size_t kMaxFieldCells = size_t{1} << 22;

Status check_options(const MatcherOptions& o) {
  if (!(o.field_sigma_m > 0.0) || !std::isfinite(o.field_sigma_m)) return Error{"field_sigma_m must be > 0"};
  if (!(o.linear_step_m >= 0.0) || !(o.angular_step_rad >= 0.0)) return Error{"search steps must be >= 0"};
  if (!(o.independent_points > 0.0)) return Error{"independent_points must be > 0"};
  if (!(o.distinct_separation_m > 0.0)) return Error{"distinct_separation_m must be > 0"};
  if (o.min_points < 1) return Error{"min_points must be >= 1"};
  return {};
}

Status check_input(const GridView& grid, std::span<const Vec2> points, const Pose& predicted,
                   const SearchWindow& window, int min_points) {
  const GridGeometry& geo = grid.geometry;
  if (geo.cells() == 0 || grid.classes.size() != geo.cells() || !(geo.resolution > 0.0))
    return Error{"scan match: the grid view is empty or inconsistent"};
  if (points.size() < static_cast<size_t>(min_points))
    return Error{"scan match: " + std::to_string(points.size()) + " points, at least " +
                 std::to_string(min_points) + " needed"};
  if (!is_finite(predicted)) return Error{"scan match: predicted pose is not finite"};
  if (!(window.linear_m >= 0.0) || !(window.angular_rad >= 0.0) || !std::isfinite(window.linear_m) ||
      !std::isfinite(window.angular_rad))
    return Error{"scan match: search window must be finite and >= 0"};
  for (const Vec2& p : points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return Error{"scan match: a point is not finite"};
  return {};
}

CellBox grown(const CellBox& box, int32_t margin) {
  return {box.x0 - margin, box.y0 - margin, box.width + 2 * margin, box.height + 2 * margin};
}

}  // namespace

bool DistinctMatch::accepts(const MatchResult& m) const {
  return m.flat_directions == 0 && !m.at_window_edge && m.ambiguity <= max_ambiguity &&
         m.covariance(0, 0) <= max_sigma_m * max_sigma_m && m.covariance(1, 1) <= max_sigma_m * max_sigma_m &&
         m.covariance(2, 2) <= max_sigma_rad * max_sigma_rad;
}

ScanMatcher::ScanMatcher(const MatcherOptions& options) : options_(options), field_(options.field_sigma_m) {}

Result<MatchResult> ScanMatcher::match(const GridView& grid, std::span<const Vec2> points,
                                       const Pose& predicted, const SearchWindow& window,
                                       double independent_points) {
  SLAM_TRY(check_options(options_));
  SLAM_TRY(check_input(grid, points, predicted, window, options_.min_points));
  const GridGeometry& geo = grid.geometry;
  const double res = geo.resolution;
  double max_range = 0.0, squared_range = 0.0;
  for (const Vec2& p : points) {
    max_range = std::max(max_range, norm(p));
    squared_range += p.x * p.x + p.y * p.y;
  }
  const size_t n = points.size();
  const double rms_range = std::max(res, std::sqrt(squared_range / static_cast<double>(n)));

  // 1. The likelihood field over every cell a candidate reads.
  const SearchLattice lattice =
      SearchLattice::around(window, res, max_range, options_.linear_step_m, options_.angular_step_rad);
  const Result<CellBox> read = CorrelativeSearch::cells_read(geo, points, predicted, window, lattice);
  if (!read) return read.error();
  if (!field_.build(grid, grown(*read, kInterpolationMargin), kMaxFieldCells))
    return Error{"scan match: the keyframe spreads over too many cells to search"};

  // 2. The correlative search.
  search_.score(field_, geo, points, predicted, lattice);
  const size_t best_index = search_.best(lattice, Eigen::Vector3d(1.0, 1.0, rms_range));
  const Eigen::Vector3d best_offset = lattice.offset(best_index);
  const Pose best{predicted.x + best_offset.x(), predicted.y + best_offset.y(),
                  wrap_angle(predicted.theta + best_offset.z())};

  // 3. The uncertainty, from the whole response.
  const double independent = independent_points > 0.0 ? independent_points : options_.independent_points;
  const ResponseSpread spread = response_spread(
      SpreadInputs{search_.sums(), &lattice, best_index, rms_range,
                   std::max(1.0, static_cast<double>(n) / independent), options_.distinct_separation_m, res});

  // 4. The refinement, kept when it stays within one step of the window and scores no worse.
  const FieldRefinement refined = refine_on_field(field_, geo, points, best, options_.refine_iterations);
  const bool refined_inside =
      std::abs(refined.pose.x - predicted.x) <= window.linear_m + lattice.step_m &&
      std::abs(refined.pose.y - predicted.y) <= window.linear_m + lattice.step_m &&
      std::abs(wrap_angle(refined.pose.theta - predicted.theta)) <= window.angular_rad + lattice.angular_step;
  const bool use_refined = refined.converged && refined_inside && refined.score >= refined.start_score;

  MatchResult result;
  result.pose = use_refined ? refined.pose : best;
  result.score = use_refined ? refined.score : refined.start_score;
  result.covariance = spread.covariance;
  result.flat_directions = spread.flat_directions;
  result.ambiguity = spread.ambiguity;
  result.at_window_edge = lattice.on_edge(best_offset);
  for (const Vec2& p : points) result.points_used += geo.cell_at(result.pose.transform(p)) ? 1 : 0;
  if (result.score < options_.min_score)
    return Error{"scan match: best score " + std::to_string(result.score) + " below " +
                 std::to_string(options_.min_score)};
  return result;
}

}  // namespace slam::correction

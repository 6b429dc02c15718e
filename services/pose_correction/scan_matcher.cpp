#include "pose_correction/scan_matcher.hpp"

#include <ceres/ceres.h>
#include <ceres/cubic_interpolation.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "common/core/cell_class.hpp"

namespace slam::correction {
namespace {

// Floor of the reported covariance: the search cannot resolve below its own discretisation.
constexpr double kFloorLinearCells = 0.5;
constexpr double kFloorAngularRad = 0.5 * std::numbers::pi / 180.0;
// Field cells kept around every lookup so bicubic interpolation near the edge reads real values.
constexpr int32_t kInterpolationMargin = 2;
// The Gaussian is cut where it has fallen below 1 %: three sigma.
constexpr double kKernelReachSigmas = 3.0;
// A keyframe whose search would need a larger field is refused rather than matched slowly.
constexpr size_t kMaxFieldCells = size_t{1} << 22;
// Candidates weighing less than this relative to the best do not change the covariance. The summed
// likelihood saturates (a point far from any wall scores 0, not minus its squared distance), so the
// many poor candidates of a wide window would otherwise outweigh the peak together.
constexpr double kNegligibleWeight = 0.05;
// Share of a window-wide uniform spread above which a direction counts as flat: a Gaussian response
// whose sigma reaches half the window's half-width already spreads this much once truncated.
constexpr double kFlatShare = 0.55;

bool is_occupied(uint8_t cell_class) {
  return (cell_class & kCellStateMask) == kCellOccupied || (cell_class & kCellObstructed) != 0;
}

using FieldGrid = ceres::Grid2D<float, 1>;
using FieldInterpolator = ceres::BiCubicInterpolator<FieldGrid>;

// Continuous field coordinates of map point (x, y): sample (row, col) is the centre of field cell
// (field_box.x0 + col, field_box.y0 + row).
struct FieldFrame {
  Vec2 origin;  // map position of the field's cell (0, 0) centre
  double inverse_resolution = 1.0;
};

// Residuals 1 - field(pose ∘ p) for every point: zero when each point sits on an occupied cell.
struct FieldResiduals {
  std::span<const Vec2> points;
  const FieldInterpolator* field;
  FieldFrame frame;

  template <class T>
  bool operator()(const T* pose, T* residuals) const {
    using std::cos, std::sin;
    const T c = cos(pose[2]), s = sin(pose[2]);
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec2 p = points[i];
      const T col = (pose[0] + c * p.x - s * p.y - frame.origin.x) * frame.inverse_resolution;
      const T row = (pose[1] + s * p.x + c * p.y - frame.origin.y) * frame.inverse_resolution;
      T likelihood;
      field->Evaluate(row, col, &likelihood);
      residuals[i] = T(1.0) - likelihood;
    }
    return true;
  }
};

// Mean likelihood of the points at `pose`, interpolated as the refinement sees it, clamped to 0..1.
double mean_likelihood(const FieldInterpolator& field, const FieldFrame& frame, std::span<const Vec2> points,
                       const Pose& pose) {
  double sum = 0.0;
  for (const Vec2& p : points) {
    const Vec2 q = pose.transform(p);
    double likelihood = 0.0;
    field.Evaluate((q.y - frame.origin.y) * frame.inverse_resolution,
                   (q.x - frame.origin.x) * frame.inverse_resolution, &likelihood);
    sum += std::clamp(likelihood, 0.0, 1.0);
  }
  return sum / static_cast<double>(points.size());
}

Status check_options(const MatcherOptions& o) {
  if (!(o.field_sigma_m > 0.0) || !std::isfinite(o.field_sigma_m)) return Error{"field_sigma_m must be > 0"};
  if (!(o.linear_step_m >= 0.0) || !(o.angular_step_rad >= 0.0)) return Error{"search steps must be >= 0"};
  if (!(o.independent_points > 0.0)) return Error{"independent_points must be > 0"};
  if (!(o.distinct_separation_m > 0.0)) return Error{"distinct_separation_m must be > 0"};
  if (o.min_points < 1) return Error{"min_points must be >= 1"};
  return {};
}

}  // namespace

bool DistinctMatch::accepts(const MatchResult& m) const {
  return m.flat_directions == 0 && !m.at_window_edge && m.ambiguity <= max_ambiguity &&
         m.covariance(0, 0) <= max_sigma_m * max_sigma_m && m.covariance(1, 1) <= max_sigma_m * max_sigma_m &&
         m.covariance(2, 2) <= max_sigma_rad * max_sigma_rad;
}

ScanMatcher::ScanMatcher(const MatcherOptions& options) : options_(options) {}

Result<MatchResult> ScanMatcher::match(const GridView& grid, std::span<const Vec2> points,
                                       const Pose& predicted, const SearchWindow& window,
                                       double independent_points) {
  SLAM_TRY(check_options(options_));
  const GridGeometry& geo = grid.geometry;
  if (geo.cells() == 0 || grid.classes.size() != geo.cells() || !(geo.resolution > 0.0))
    return Error{"scan match: the grid view is empty or inconsistent"};
  if (points.size() < static_cast<size_t>(options_.min_points))
    return Error{"scan match: " + std::to_string(points.size()) + " points, at least " +
                 std::to_string(options_.min_points) + " needed"};
  if (!is_finite(predicted)) return Error{"scan match: predicted pose is not finite"};
  if (!(window.linear_m >= 0.0) || !(window.angular_rad >= 0.0) || !std::isfinite(window.linear_m) ||
      !std::isfinite(window.angular_rad))
    return Error{"scan match: search window must be finite and >= 0"};
  double max_range = 0.0;
  for (const Vec2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return Error{"scan match: a point is not finite"};
    max_range = std::max(max_range, norm(p));
  }

  // The search lattice: x/y steps are whole cells so a candidate is one lookup per point.
  const double res = geo.resolution;
  const int32_t step_cells =
      options_.linear_step_m > 0.0
          ? std::max<int32_t>(1, static_cast<int32_t>(std::lround(options_.linear_step_m / res)))
          : 1;
  const double step_m = step_cells * res;
  const int32_t linear_steps = static_cast<int32_t>(std::ceil(window.linear_m / step_m - 1e-9));
  const double nominal_angular_step =
      options_.angular_step_rad > 0.0 ? options_.angular_step_rad : res / std::max(max_range, res);
  const int32_t angular_steps =
      static_cast<int32_t>(std::ceil(window.angular_rad / nominal_angular_step - 1e-9));
  const double angular_step = angular_steps > 0 ? window.angular_rad / angular_steps : 0.0;
  const int32_t side = 2 * linear_steps + 1;
  const int32_t headings = 2 * angular_steps + 1;
  const int32_t reach_offset = linear_steps * step_cells;

  // The field covers every cell any candidate looks up, plus the interpolation margin.
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x;
  double hi_x = -lo_x, hi_y = -lo_x;
  for (const Vec2& p : points) {
    const Vec2 g = geo.to_grid(predicted.transform(p));
    const double sweep = norm(p) * window.angular_rad / res;  // arc length bounds the chord
    lo_x = std::min(lo_x, g.x - sweep);
    lo_y = std::min(lo_y, g.y - sweep);
    hi_x = std::max(hi_x, g.x + sweep);
    hi_y = std::max(hi_y, g.y + sweep);
  }
  const double limit = static_cast<double>(std::numeric_limits<int32_t>::max() / 4);
  if (!(std::abs(lo_x) < limit && std::abs(lo_y) < limit && std::abs(hi_x) < limit && std::abs(hi_y) < limit))
    return Error{"scan match: the search window lies off the grid"};
  CellBox lookups{static_cast<int32_t>(std::floor(lo_x)) - reach_offset,
                  static_cast<int32_t>(std::floor(lo_y)) - reach_offset, 0, 0};
  lookups.width = static_cast<int32_t>(std::floor(hi_x)) + reach_offset + 1 - lookups.x0;
  lookups.height = static_cast<int32_t>(std::floor(hi_y)) + reach_offset + 1 - lookups.y0;
  if (lookups.x0 >= geo.width || lookups.y0 >= geo.height || lookups.x0 + lookups.width <= 0 ||
      lookups.y0 + lookups.height <= 0)
    return Error{"scan match: the search window lies off the grid"};
  field_box_ = {lookups.x0 - kInterpolationMargin, lookups.y0 - kInterpolationMargin,
                lookups.width + 2 * kInterpolationMargin, lookups.height + 2 * kInterpolationMargin};
  if (field_box_.cells() > kMaxFieldCells)
    return Error{"scan match: the keyframe spreads over too many cells to search"};

  // Kernel: the likelihood a cell gets from an occupied cell at a given offset.
  if (kernel_resolution_ != res || kernel_.empty()) {
    const double sigma_cells = options_.field_sigma_m / res;
    kernel_radius_ = std::max(1, static_cast<int>(std::ceil(kKernelReachSigmas * sigma_cells)));
    const int span = 2 * kernel_radius_ + 1;
    kernel_.resize(static_cast<size_t>(span * span));
    for (int dy = -kernel_radius_; dy <= kernel_radius_; ++dy)
      for (int dx = -kernel_radius_; dx <= kernel_radius_; ++dx)
        kernel_[static_cast<size_t>((dy + kernel_radius_) * span + dx + kernel_radius_)] =
            static_cast<float>(std::exp(-(dx * dx + dy * dy) / (2.0 * sigma_cells * sigma_cells)));
    kernel_resolution_ = res;
  }

  // Likelihood field over field_box_ only: each occupied cell within kernel reach stamps the
  // maximum of its kernel, which is the Gaussian of the distance to the nearest occupied cell.
  const int32_t fw = field_box_.width, fh = field_box_.height, r = kernel_radius_;
  field_.assign(field_box_.cells(), 0.0f);
  const int32_t gy0 = std::max(0, field_box_.y0 - r), gy1 = std::min(geo.height, field_box_.y0 + fh + r);
  const int32_t gx0 = std::max(0, field_box_.x0 - r), gx1 = std::min(geo.width, field_box_.x0 + fw + r);
  const int span = 2 * r + 1;
  for (int32_t gy = gy0; gy < gy1; ++gy) {
    const uint8_t* row = grid.classes.data() + static_cast<size_t>(gy) * static_cast<size_t>(geo.width);
    for (int32_t gx = gx0; gx < gx1; ++gx) {
      if (!is_occupied(row[gx])) continue;
      const int32_t cx = gx - field_box_.x0, cy = gy - field_box_.y0;
      const int32_t y_from = std::max(cy - r, 0), y_to = std::min(cy + r, fh - 1);
      const int32_t x_from = std::max(cx - r, 0), x_to = std::min(cx + r, fw - 1);
      for (int32_t y = y_from; y <= y_to; ++y) {
        float* out = field_.data() + static_cast<size_t>(y) * static_cast<size_t>(fw);
        const float* k = kernel_.data() + static_cast<size_t>((y - cy + r) * span);
        for (int32_t x = x_from; x <= x_to; ++x) out[x] = std::max(out[x], k[x - cx + r]);
      }
    }
  }

  // Correlative search: per heading rotate the points once, then every x/y offset is a lookup.
  const size_t n = points.size();
  const size_t per_heading = static_cast<size_t>(side) * static_cast<size_t>(side);
  sums_.assign(per_heading * static_cast<size_t>(headings), 0.0f);
  lookup_.resize(n);
  for (int32_t h = 0; h < headings; ++h) {
    const Pose rotated{predicted.x, predicted.y, predicted.theta + (h - angular_steps) * angular_step};
    const double c = std::cos(rotated.theta), s = std::sin(rotated.theta);
    for (size_t i = 0; i < n; ++i) {
      const Vec2 g = geo.to_grid(
          {rotated.x + c * points[i].x - s * points[i].y, rotated.y + s * points[i].x + c * points[i].y});
      const int32_t cx = static_cast<int32_t>(std::floor(g.x)) - field_box_.x0 - reach_offset;
      const int32_t cy = static_cast<int32_t>(std::floor(g.y)) - field_box_.y0 - reach_offset;
      lookup_[i] = cy * fw + cx;
    }
    float* sums = sums_.data() + static_cast<size_t>(h) * per_heading;
    for (size_t i = 0; i < n; ++i) {
      for (int32_t iy = 0; iy < side; ++iy) {
        const float* row = field_.data() + lookup_[i] + iy * step_cells * fw;
        float* out = sums + static_cast<size_t>(iy) * static_cast<size_t>(side);
        for (int32_t ix = 0; ix < side; ++ix) out[ix] += row[ix * step_cells];
      }
    }
  }
  auto offset_of = [&](size_t index) -> Eigen::Vector3d {
    const auto h = static_cast<int32_t>(index / per_heading);
    const auto iy = static_cast<int32_t>(index % per_heading) / side;
    const auto ix = static_cast<int32_t>(index % per_heading) % side;
    return {(ix - linear_steps) * step_m, (iy - linear_steps) * step_m, (h - angular_steps) * angular_step};
  };
  // Offsets are compared in metres, heading counted as the arc it swings at the points' RMS range.
  double squared_range = 0.0;
  for (const Vec2& p : points) squared_range += p.x * p.x + p.y * p.y;
  const double rms_range = std::max(res, std::sqrt(squared_range / static_cast<double>(n)));
  const Eigen::Vector3d scale(1.0, 1.0, rms_range);
  // The best candidate; among equals the one nearest the prediction. Along a straight wall or a
  // corridor whole-cell shifts score exactly alike, and the first of them (the window's corner)
  // would push every such keyframe the same way.
  const float top = *std::max_element(sums_.begin(), sums_.end());
  const float tie = top - std::max(1e-5f * std::abs(top), 1e-6f);
  size_t best_index = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (size_t index = 0; index < sums_.size(); ++index) {
    if (sums_[index] < tie) continue;
    const double d = offset_of(index).cwiseProduct(scale).squaredNorm();
    if (d < best_distance) {
      best_distance = d;
      best_index = index;
    }
  }
  const double best_sum = sums_[best_index];
  const Eigen::Vector3d best_offset = offset_of(best_index);
  const auto on_edge = [](double offset, int32_t steps, double step) {
    return steps > 0 && std::abs(offset) >= (steps - 0.5) * step;
  };
  const bool at_window_edge = on_edge(best_offset.x(), linear_steps, step_m) ||
                              on_edge(best_offset.y(), linear_steps, step_m) ||
                              on_edge(best_offset.z(), angular_steps, angular_step);
  const Pose best{predicted.x + best_offset.x(), predicted.y + best_offset.y(),
                  wrap_angle(predicted.theta + best_offset.z())};

  // Covariance (Olson 2009): the weighted second moment of every candidate, each weighted by its
  // likelihood relative to the best read as a log-likelihood; ambiguous directions keep many heavy
  // candidates. Worked in metres, heading counted as the arc it swings at the points' RMS range,
  // so a flat direction mixing position and heading (a ring) is found as one eigenvector.
  const double independent = independent_points > 0.0 ? independent_points : options_.independent_points;
  const double temperature = std::max(1.0, static_cast<double>(n) / independent);
  const Eigen::Vector3d best_scaled = best_offset.cwiseProduct(scale);
  double weight_sum = 0.0, distinct_sum = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  const double min_sum = best_sum + temperature * std::log(kNegligibleWeight);
  for (size_t index = 0; index < sums_.size(); ++index) {
    const Eigen::Vector3d v = offset_of(index).cwiseProduct(scale);
    if ((v - best_scaled).norm() >= options_.distinct_separation_m)
      distinct_sum = std::max(distinct_sum, static_cast<double>(sums_[index]));
    if (sums_[index] < min_sum) continue;
    const double w = std::exp((sums_[index] - best_sum) / temperature);
    weight_sum += w;
    first += w * v;
    second += w * v * v.transpose();
  }
  const Eigen::Vector3d mean = first / weight_sum;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread(second / weight_sum - mean * mean.transpose());
  // A direction whose spread comes near that of a response flat over the whole window (uniform:
  // a third of the squared half-width along it) is not pinned by the map at all: the window, not
  // the map, bounded it. Counted, so a closure is refused; its variance is the window's own
  // (uniform) one, so tracking takes the best candidate there only weakly.
  const Eigen::Vector3d half_width(linear_steps * step_m, linear_steps * step_m,
                                   rms_range * angular_steps * angular_step);
  Eigen::Vector3d variances = spread.eigenvalues().cwiseMax(0.0);
  int flat_directions = 0;
  for (int k = 0; k < 3; ++k) {
    const double window_variance = spread.eigenvectors().col(k).cwiseProduct(half_width).squaredNorm() / 3.0;
    if (window_variance > 0.0 && variances[k] >= kFlatShare * window_variance) {
      variances[k] = std::max(variances[k], window_variance);
      ++flat_directions;
    }
  }
  const Eigen::Matrix3d unscale = scale.cwiseInverse().asDiagonal();
  Eigen::Matrix3d covariance =
      unscale * spread.eigenvectors() * variances.asDiagonal() * spread.eigenvectors().transpose() * unscale;
  covariance.diagonal() +=
      Eigen::Vector3d(kFloorLinearCells * res * kFloorLinearCells * res,
                      kFloorLinearCells * res * kFloorLinearCells * res, kFloorAngularRad * kFloorAngularRad);

  // Least-squares refinement of the best candidate on the bicubic-interpolated field.
  const FieldGrid field_grid(field_.data(), 0, fh, 0, fw);
  const FieldInterpolator interpolator(field_grid);
  const FieldFrame frame{geo.centre({field_box_.x0, field_box_.y0}), 1.0 / res};
  double pose_params[3] = {best.x, best.y, best.theta};
  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<FieldResiduals, ceres::DYNAMIC, 3>(
                               new FieldResiduals{points, &interpolator, frame}, static_cast<int>(n)),
                           nullptr, pose_params);
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options_.refine_iterations;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  // The refinement must stay within one search step of the window and must not score worse.
  const Pose refined{pose_params[0], pose_params[1], wrap_angle(pose_params[2])};
  const double best_score = mean_likelihood(interpolator, frame, points, best);
  const double refined_score = mean_likelihood(interpolator, frame, points, refined);
  const bool refined_inside =
      std::abs(refined.x - predicted.x) <= window.linear_m + step_m &&
      std::abs(refined.y - predicted.y) <= window.linear_m + step_m &&
      std::abs(wrap_angle(refined.theta - predicted.theta)) <= window.angular_rad + angular_step;
  const bool use_refined =
      summary.IsSolutionUsable() && refined_inside && is_finite(refined) && refined_score >= best_score;

  MatchResult result;
  result.pose = use_refined ? refined : best;
  result.score = use_refined ? refined_score : best_score;
  result.covariance = covariance;
  result.flat_directions = flat_directions;
  result.ambiguity = best_sum > 0.0 ? distinct_sum / best_sum : 0.0;
  result.at_window_edge = at_window_edge;
  for (const Vec2& p : points) result.points_used += geo.cell_at(result.pose.transform(p)) ? 1 : 0;
  if (result.score < options_.min_score)
    return Error{"scan match: best score " + std::to_string(result.score) + " below " +
                 std::to_string(options_.min_score)};
  return result;
}

}  // namespace slam::correction

#include "pose_correction/point_refiner.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace slam::correction {
namespace {

// A reference cloud spread wider than this many bins is not binned (a keyframe's surroundings span
// a few hundred).
constexpr size_t kMaxBins = size_t{1} << 22;
// Iterations stop once a step moves the pose less than this (metres; heading as radians).
constexpr double kConverged = 1e-4;

}  // namespace

void PointRefiner::set_reference(std::span<const Vec2> points) {
  points_.clear();
  bin_start_.clear();
  columns_ = rows_ = 0;
  if (points.empty()) return;
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 hi{-lo.x, -lo.y};
  for (const Vec2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  if (!(lo.x <= hi.x)) return;
  const double cell = options_.reach_m;
  const double columns = std::floor((hi.x - lo.x) / cell) + 1.0;
  const double rows = std::floor((hi.y - lo.y) / cell) + 1.0;
  if (columns * rows > static_cast<double>(kMaxBins)) return;
  origin_ = lo;
  columns_ = static_cast<int32_t>(columns);
  rows_ = static_cast<int32_t>(rows);

  // Counting sort by bin.
  const size_t bins = static_cast<size_t>(columns_) * static_cast<size_t>(rows_);
  bin_start_.assign(bins + 1, 0);
  bin_of_.clear();
  for (const Vec2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      bin_of_.push_back(std::numeric_limits<uint32_t>::max());
      continue;
    }
    const auto column = std::min(columns_ - 1, static_cast<int32_t>((p.x - origin_.x) / cell));
    const auto row = std::min(rows_ - 1, static_cast<int32_t>((p.y - origin_.y) / cell));
    const auto bin = static_cast<uint32_t>(row * columns_ + column);
    bin_of_.push_back(bin);
    ++bin_start_[bin + 1];
  }
  for (size_t b = 0; b < bins; ++b) bin_start_[b + 1] += bin_start_[b];
  points_.resize(bin_start_[bins]);
  // bin_start_[b] is used as the fill cursor of bin b, then restored by one shift.
  for (size_t i = 0; i < points.size(); ++i) {
    if (bin_of_[i] == std::numeric_limits<uint32_t>::max()) continue;
    points_[bin_start_[bin_of_[i]]++] = points[i];
  }
  for (size_t b = bins; b > 0; --b) bin_start_[b] = bin_start_[b - 1];
  bin_start_[0] = 0;
}

std::optional<PointRefiner::Line> PointRefiner::line_near(Vec2 q) const {
  const double cell = options_.reach_m;
  const auto column = static_cast<int32_t>(std::floor((q.x - origin_.x) / cell));
  const auto row = static_cast<int32_t>(std::floor((q.y - origin_.y) / cell));
  const double reach_sq = options_.reach_m * options_.reach_m;
  // Moments of the reference points within reach, about q (small numbers, no cancellation).
  int count = 0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (int32_t r = std::max(0, row - 1); r <= std::min(rows_ - 1, row + 1); ++r) {
    for (int32_t c = std::max(0, column - 1); c <= std::min(columns_ - 1, column + 1); ++c) {
      const auto bin = static_cast<size_t>(r * columns_ + c);
      for (uint32_t i = bin_start_[bin]; i < bin_start_[bin + 1]; ++i) {
        const Vec2 d = points_[i] - q;
        if (dot(d, d) > reach_sq) continue;
        ++count;
        sx += d.x;
        sy += d.y;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
      }
    }
  }
  if (count < options_.min_line_points) return std::nullopt;
  const double n = count;
  const double mx = sx / n, my = sy / n;
  const double cxx = sxx / n - mx * mx, cxy = sxy / n - mx * my, cyy = syy / n - my * my;
  // Eigenvalues of the 2x2 scatter: the line runs along the larger one's vector.
  const double half_trace = 0.5 * (cxx + cyy);
  const double root = std::sqrt(std::max(0.0, 0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy));
  const double across = half_trace - root, along = half_trace + root;
  if (across > options_.max_line_thickness_m * options_.max_line_thickness_m) return std::nullopt;
  if (along < options_.min_line_length_m * options_.min_line_length_m) return std::nullopt;
  // The normal: the eigenvector of the smaller eigenvalue.
  Vec2 normal =
      std::abs(cxy) > 1e-15 ? Vec2{cxy, across - cxx} : (cxx < cyy ? Vec2{1.0, 0.0} : Vec2{0.0, 1.0});
  normal = normal * (1.0 / norm(normal));
  return Line{{q.x + mx, q.y + my}, normal};
}

std::optional<PointRefinement> PointRefiner::refine(std::span<const Vec2> points, const Pose& start,
                                                    const Eigen::Matrix3d& start_cov) const {
  if (points.empty() || points_.empty()) return std::nullopt;
  const Eigen::Matrix3d prior = start_cov.inverse();
  if (!prior.allFinite()) return std::nullopt;
  const double point_information = 1.0 / (options_.point_sigma_m * options_.point_sigma_m);
  const auto min_inliers =
      static_cast<int>(std::ceil(options_.min_inlier_share * static_cast<double>(points.size())));

  Pose pose = start;
  int inliers = 0;
  for (int iteration = 0; iteration < options_.iterations; ++iteration) {
    Eigen::Matrix3d h = prior;
    const Eigen::Vector3d offset(pose.x - start.x, pose.y - start.y, wrap_angle(pose.theta - start.theta));
    Eigen::Vector3d g = prior * offset;
    inliers = 0;
    for (const Vec2& p : points) {
      const Vec2 q = pose.transform(p);
      const auto line = line_near(q);
      if (!line) continue;
      ++inliers;
      const double e = dot(line->normal, q - line->centre);
      // d q / d theta is the arm q - t turned a quarter; its component along the normal.
      const Vec2 arm = q - pose.position();
      const Eigen::Vector3d j(line->normal.x, line->normal.y, cross(arm, line->normal));
      const double w =
          point_information * (std::abs(e) <= options_.huber_m ? 1.0 : options_.huber_m / std::abs(e));
      h += w * j * j.transpose();
      g += w * j * e;
    }
    if (inliers < min_inliers) return std::nullopt;
    const Eigen::Vector3d step = -h.ldlt().solve(g);
    if (!step.allFinite()) return std::nullopt;
    pose = {pose.x + step.x(), pose.y + step.y(), wrap_angle(pose.theta + step.z())};
    if (step.head<2>().norm() < kConverged && std::abs(step.z()) < kConverged) break;
  }
  if (distance(pose.position(), start.position()) > options_.max_shift_m ||
      std::abs(wrap_angle(pose.theta - start.theta)) > options_.max_turn_rad)
    return std::nullopt;
  return PointRefinement{pose, inliers};
}

}  // namespace slam::correction

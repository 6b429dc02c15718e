#include "pose_correction/branch_and_bound_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace slam::correction {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool better(const auto& a, const auto& b) {
  return a.score > b.score;
}

}  // namespace

BranchAndBoundSearch::BranchAndBoundSearch(const BranchAndBoundOptions& options)
    : options_(options), field_(options.field_sigma_m) {}

Status BranchAndBoundSearch::set_map(const GridView& grid) {
  levels_.clear();
  const GridGeometry& geo = grid.geometry;
  if (geo.cells() == 0 || grid.classes.size() != geo.cells() || !(geo.resolution > 0.0))
    return Error{"global search: the map is empty or inconsistent"};
  if (options_.depth < 0 || options_.depth > 12) return Error{"global search: depth must be 0..12"};
  geometry_ = geo;
  margin_ = int32_t{1} << options_.depth;
  level_width_ = geo.width + 2 * margin_;
  level_height_ = geo.height + 2 * margin_;
  const CellBox box{-margin_, -margin_, level_width_, level_height_};
  if (box.cells() * static_cast<size_t>(options_.depth + 1) > options_.max_map_cells)
    return Error{"global search: the map has too many cells (" + std::to_string(geo.cells()) + ")"};
  SLAM_TRY(field_.build(grid, box, options_.max_map_cells));
  levels_.emplace_back(field_.values().begin(), field_.values().end());
  const auto w = static_cast<size_t>(level_width_);
  for (int d = 1; d <= options_.depth; ++d) {
    // Level d at (x, y): the maximum of level d-1 over the four blocks of half its side from (x, y).
    const std::vector<float>& below = levels_.back();
    const int32_t half = int32_t{1} << (d - 1);
    std::vector<float> level(below.size(), 0.0f);
    for (int32_t y = 0; y < level_height_; ++y) {
      const bool up = y + half < level_height_;
      for (int32_t x = 0; x < level_width_; ++x) {
        const size_t i = static_cast<size_t>(y) * w + static_cast<size_t>(x);
        float m = below[i];
        const bool right = x + half < level_width_;
        if (right) m = std::max(m, below[i + static_cast<size_t>(half)]);
        if (up) m = std::max(m, below[i + static_cast<size_t>(half) * w]);
        if (right && up)
          m = std::max(m, below[i + static_cast<size_t>(half) * w + static_cast<size_t>(half)]);
        level[i] = m;
      }
    }
    levels_.push_back(std::move(level));
  }
  return {};
}

void BranchAndBoundSearch::prepare_headings(std::span<const Vec2> points, const SearchRegion& region) {
  points_.clear();
  double max_range = 0.0, squared = 0.0;
  for (const Vec2& p : points) {
    const double r = norm(p);
    if (!(r <= options_.max_point_range_m)) continue;
    points_.push_back(p);
    max_range = std::max(max_range, r);
    squared += r * r;
  }
  const double res = geometry_.resolution;
  rms_range_ =
      points_.empty() ? res : std::max(res, std::sqrt(squared / static_cast<double>(points_.size())));
  const double step = res / std::max(max_range, res);
  headings_.clear();
  if (region.angular_rad >= std::numbers::pi) {
    const auto n = static_cast<int32_t>(std::ceil(kTwoPi / step));
    for (int32_t k = 0; k < n; ++k) headings_.push_back(wrap_angle(region.centre.theta + k * kTwoPi / n));
  } else {
    const auto n = static_cast<int32_t>(std::ceil(region.angular_rad / step - 1e-9));
    const double exact = n > 0 ? region.angular_rad / n : 0.0;
    for (int32_t k = -n; k <= n; ++k) headings_.push_back(wrap_angle(region.centre.theta + k * exact));
  }
  rotated_.resize(headings_.size() * points_.size());
  for (size_t h = 0; h < headings_.size(); ++h) {
    const double c = std::cos(headings_[h]), s = std::sin(headings_[h]);
    for (size_t i = 0; i < points_.size(); ++i) {
      const Vec2& p = points_[i];
      const Vec2 g =
          geometry_.to_grid({region.centre.x + c * p.x - s * p.y, region.centre.y + s * p.x + c * p.y});
      rotated_[h * points_.size() + i] = {static_cast<int32_t>(std::floor(g.x)) + margin_,
                                          static_cast<int32_t>(std::floor(g.y)) + margin_};
    }
  }
}

float BranchAndBoundSearch::bound(const Candidate& c) const {
  const std::vector<float>& level = levels_[static_cast<size_t>(c.depth)];
  const Cell* cells = rotated_.data() + static_cast<size_t>(c.heading) * points_.size();
  float sum = 0.0f;
  for (size_t i = 0; i < points_.size(); ++i) {
    const int32_t x = cells[i].x + c.x, y = cells[i].y + c.y;
    if (x < 0 || y < 0 || x >= level_width_ || y >= level_height_) continue;
    sum += level[static_cast<size_t>(y) * static_cast<size_t>(level_width_) + static_cast<size_t>(x)];
  }
  return sum;
}

double BranchAndBoundSearch::separation(const Candidate& a, const Candidate& b) const {
  const double res = geometry_.resolution;
  const double dx = (a.x - b.x) * res, dy = (a.y - b.y) * res;
  const double arc = rms_range_ * wrap_angle(headings_[static_cast<size_t>(a.heading)] -
                                             headings_[static_cast<size_t>(b.heading)]);
  return std::sqrt(dx * dx + dy * dy + arc * arc);
}

void BranchAndBoundSearch::branch(const Candidate& node, float& threshold, Leaf& best, const Leaf* exclude) {
  if (node.depth == 0) {
    if (exclude && separation(node, exclude->candidate) < options_.distinct_separation_m) return;
    if (node.score > threshold) {
      threshold = node.score;
      best = {node, true};
    }
    return;
  }
  // The four children, best first; each opened only while it can still beat the best leaf.
  const int32_t half = int32_t{1} << (node.depth - 1);
  std::array<Candidate, 4> children;
  size_t count = 0;
  for (int32_t dy : {0, half}) {
    for (int32_t dx : {0, half}) {
      Candidate child{node.heading, node.x + dx, node.y + dy, node.depth - 1, 0.0f};
      if (child.x > reach_cells_ || child.y > reach_cells_) continue;
      child.score = bound(child);
      ++nodes_scored_;
      size_t at = count++;  // insertion, best first
      for (; at > 0 && children[at - 1].score < child.score; --at) children[at] = children[at - 1];
      children[at] = child;
    }
  }
  for (size_t k = 0; k < count; ++k) {
    if (children[k].score <= threshold) break;
    branch(children[k], threshold, best, exclude);
  }
}

Pose BranchAndBoundSearch::pose_of(const Candidate& c) const {
  const double res = geometry_.resolution;
  return {c.x * res, c.y * res, headings_[static_cast<size_t>(c.heading)]};
}

Result<GlobalMatch> BranchAndBoundSearch::search(std::span<const Vec2> points, const SearchRegion& region) {
  if (levels_.empty()) return Error{"global search: no map"};
  if (!is_finite(region.centre) || !(region.linear_m >= 0.0) || !std::isfinite(region.linear_m) ||
      !(region.angular_rad >= 0.0))
    return Error{"global search: the region must be finite"};
  for (const Vec2& p : points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return Error{"global search: a point is not finite"};
  const double res = geometry_.resolution;
  const Vec2 centre_cell = geometry_.to_grid(region.centre.position());
  const double extent = std::max(level_width_, level_height_) + region.linear_m / res;
  if (!(std::abs(centre_cell.x) < extent && std::abs(centre_cell.y) < extent))
    return Error{"global search: the region lies off the map"};
  prepare_headings(points, region);
  if (points_.size() < static_cast<size_t>(std::max(options_.min_points, 1)))
    return Error{"global search: " + std::to_string(points_.size()) + " points within range, at least " +
                 std::to_string(options_.min_points) + " needed"};
  reach_cells_ = static_cast<int32_t>(std::ceil(region.linear_m / res - 1e-9));
  nodes_scored_ = 0;

  // The top level: every heading, translations in blocks of 2^depth cells, best first.
  const int32_t top_side = int32_t{1} << options_.depth;
  top_.clear();
  for (int32_t h = 0; h < static_cast<int32_t>(headings_.size()); ++h) {
    for (int32_t y = -reach_cells_; y <= reach_cells_; y += top_side) {
      for (int32_t x = -reach_cells_; x <= reach_cells_; x += top_side) {
        Candidate c{h, x, y, options_.depth, 0.0f};
        c.score = bound(c);
        top_.push_back(c);
      }
    }
  }
  nodes_scored_ += top_.size();
  std::sort(top_.begin(), top_.end(), better<Candidate, Candidate>);

  const auto n = static_cast<float>(points_.size());
  const auto run = [&](float threshold, const Leaf* exclude) {
    Leaf leaf;
    for (const Candidate& c : top_) {
      if (c.score <= threshold) break;
      branch(c, threshold, leaf, exclude);
    }
    return leaf;
  };
  const Leaf best = run(static_cast<float>(options_.min_score) * n, nullptr);
  if (!best.found) return Error{"global search: no pose scores " + std::to_string(options_.min_score)};
  const Leaf runner_up = run(std::max(static_cast<float>(options_.min_score) * n,
                                      static_cast<float>(options_.runner_up_floor) * best.candidate.score),
                             &best);

  GlobalMatch match;
  const Pose offset = pose_of(best.candidate);
  match.pose = {region.centre.x + offset.x, region.centre.y + offset.y, offset.theta};
  match.score = best.candidate.score / n;
  match.runner_up_score = runner_up.found ? runner_up.candidate.score / n : 0.0;
  match.nodes_scored = nodes_scored_;
  return match;
}

}  // namespace slam::correction

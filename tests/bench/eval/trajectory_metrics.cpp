// ATE and the rigid 2-D fit (see trajectory_metrics.hpp).
#include "eval/trajectory_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace slam::bench {
namespace {

Vec2 centroid(std::span<const Vec2> points) {
  Vec2 sum;
  for (const Vec2& p : points) sum = sum + p;
  return points.empty() ? sum : sum * (1.0 / static_cast<double>(points.size()));
}

}  // namespace

ErrorStats summarise(std::span<const double> errors) {
  ErrorStats s;
  s.count = errors.size();
  if (errors.empty()) return s;
  double sum = 0.0, sum_sq = 0.0;
  for (const double e : errors) {
    sum += e;
    sum_sq += e * e;
    s.max = std::max(s.max, e);
  }
  s.mean = sum / static_cast<double>(errors.size());
  s.rmse = std::sqrt(sum_sq / static_cast<double>(errors.size()));
  return s;
}

ErrorStats position_errors(std::span<const Vec2> estimate, std::span<const Vec2> truth) {
  std::vector<double> errors(std::min(estimate.size(), truth.size()));
  for (size_t i = 0; i < errors.size(); ++i) errors[i] = distance(estimate[i], truth[i]);
  return summarise(errors);
}

Pose fit_rigid(std::span<const Vec2> estimate, std::span<const Vec2> truth) {
  const size_t n = std::min(estimate.size(), truth.size());
  const Vec2 ce = centroid(estimate.first(n));
  const Vec2 ct = centroid(truth.first(n));
  // The rotation maximising sum (R e_i) . t_i for centred points: atan2 of the summed cross and
  // dot products (the SVD of the 2x2 covariance in closed form).
  double dots = 0.0, crosses = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 e = estimate[i] - ce, t = truth[i] - ct;
    dots += dot(e, t);
    crosses += cross(e, t);
  }
  const double theta = (dots == 0.0 && crosses == 0.0) ? 0.0 : std::atan2(crosses, dots);
  const Vec2 rotated = Pose{0.0, 0.0, theta}.transform(ce);
  return {ct.x - rotated.x, ct.y - rotated.y, theta};
}

std::vector<Vec2> transformed(const Pose& transform, std::span<const Vec2> points) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const Vec2& p : points) out.push_back(transform.transform(p));
  return out;
}

TrajectoryErrors trajectory_errors(std::span<const TrajectorySample> samples, bool align) {
  TrajectoryErrors out;
  std::vector<Vec2> truth, corrected;
  std::map<std::string, std::pair<std::vector<Vec2>, std::vector<Vec2>>> raw_by_robot;  // raw, truth
  for (const TrajectorySample& s : samples) {
    truth.push_back(s.truth);
    corrected.push_back(s.corrected);
    auto& [raw, robot_truth] = raw_by_robot[s.robot_id];
    raw.push_back(s.raw);
    robot_truth.push_back(s.truth);
  }
  if (align) {
    out.alignment = fit_rigid(corrected, truth);
    corrected = transformed(out.alignment, corrected);
  }
  out.corrected = position_errors(corrected, truth);

  std::vector<double> raw_errors;
  for (auto& [robot, pair] : raw_by_robot) {
    auto& [raw, robot_truth] = pair;
    if (align) raw = transformed(fit_rigid(raw, robot_truth), raw);
    for (size_t i = 0; i < raw.size(); ++i) raw_errors.push_back(distance(raw[i], robot_truth[i]));
  }
  out.raw = summarise(raw_errors);
  return out;
}

}  // namespace slam::bench

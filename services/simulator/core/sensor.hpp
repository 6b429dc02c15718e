#pragma once
// Range beams: where they point, and how a true range becomes a reported one (Gaussian noise,
// dropouts) plus an obstacle point placed from the believed pose.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "simulator/core/config.hpp"
#include "simulator/core/geometry.hpp"
#include "simulator/core/report.hpp"

namespace slam::sim {

// Beam angles relative to the heading: evenly around the circle for a full field of view (no
// beam twice at +-pi), else from -fov/2 to +fov/2 inclusive.
inline void beam_angles(const SensorConfig& c, std::vector<double>& out) {
  out.resize(static_cast<size_t>(c.beams));
  const bool full = c.fov >= 2.0 * std::numbers::pi - 1e-9;
  for (int i = 0; i < c.beams; ++i) {
    if (full)
      out[static_cast<size_t>(i)] = wrap_angle(c.fov * i / c.beams);
    else
      out[static_cast<size_t>(i)] = c.beams == 1 ? 0.0 : -0.5 * c.fov + c.fov * i / (c.beams - 1);
  }
}

// Fills out.angles/ranges/hits/max_range. cast(origin, unit_dir, max_range) returns the true
// distance to the nearest obstacle or max_range. Allocation-free once `out` has been used before.
template <class Cast>
void scan(const SensorConfig& c, const Pose& truth, const Pose& believed, std::mt19937_64& rng, Cast&& cast,
          RobotReport& out) {
  beam_angles(c, out.angles);
  out.ranges.resize(out.angles.size());
  out.hits.clear();
  out.max_range = c.max_range;
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (size_t i = 0; i < out.angles.size(); ++i) {
    const double a = out.angles[i];
    const Vec2 dir{std::cos(truth.theta + a), std::sin(truth.theta + a)};
    double r = cast(Vec2{truth.x, truth.y}, dir, c.max_range);
    if (c.dropout > 0.0 && unit(rng) < c.dropout) r = c.max_range;
    if (r < c.max_range && c.range_noise_sd > 0.0) r = std::max(0.0, r + c.range_noise_sd * noise(rng));
    if (r >= c.max_range) {
      out.ranges[i] = c.max_range;
      continue;
    }
    out.ranges[i] = r;
    const double b = believed.theta + a;
    out.hits.push_back({believed.x + r * std::cos(b), believed.y + r * std::sin(b)});
  }
}

}  // namespace slam::sim

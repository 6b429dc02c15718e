// RobotFootprints: hits on other robots become misses.
#include "mapper/core/robot_footprints.hpp"

#include <algorithm>
#include <cmath>

namespace slam::mapper {

Status validate(const FootprintConfig& config) {
  if (!std::isfinite(config.radius_m) || config.radius_m < 0.0 || config.radius_m > 5.0)
    return Error{"robot_filter.radius_m must be between 0 and 5 (0 turns the filter off)"};
  if (!std::isfinite(config.max_age_s) || config.max_age_s <= 0.0 || config.max_age_s > 3600.0)
    return Error{"robot_filter.max_age_s must be above 0 and at most 3600"};
  return Status::ok();
}

RobotFootprints::RobotFootprints(const FootprintConfig& config)
    : radius2_(config.radius_m * config.radius_m),
      max_age_ns_(static_cast<int64_t>(config.max_age_s * 1e9)) {}

size_t RobotFootprints::apply(std::string_view robot_id, Vec2 position, int64_t now_ns,
                              std::vector<Vec2>& hits, std::vector<Vec2>& misses,
                              std::vector<Vec2>* odom_hits, std::vector<Vec2>* odom_misses) {
  size_t self = sightings_.size();
  if (auto it = slots_.find(robot_id); it != slots_.end()) {
    self = it->second;
  } else {
    slots_.emplace(std::string(robot_id), self);
    sightings_.push_back({});
  }
  const auto distance2 = [](Vec2 a, Vec2 b) { return dot(a - b, a - b); };
  size_t moved = 0;
  if (radius2_ > 0.0 && !hits.empty()) {
    // Only robots within reach of this observation's farthest hit can be in it.
    double reach2 = 0.0;
    for (const Vec2& p : hits) reach2 = std::max(reach2, distance2(p, position));
    const double reach = std::sqrt(reach2) + std::sqrt(radius2_);
    near_.clear();
    for (size_t i = 0; i < sightings_.size(); ++i) {
      const Sighting& o = sightings_[i];
      if (i == self || now_ns - o.seen_ns > max_age_ns_) continue;
      if (distance2(o.position, position) <= reach * reach) near_.push_back(o.position);
    }
    if (!near_.empty()) {
      const auto on_robot = [&](const Vec2& p) {
        return std::any_of(near_.begin(), near_.end(), [&](Vec2 o) { return distance2(p, o) <= radius2_; });
      };
      // Stable: the remaining hits keep their order; moved ones go to the misses.
      const bool mirrored = odom_hits && odom_misses && odom_hits->size() == hits.size();
      size_t keep = 0;
      for (size_t i = 0; i < hits.size(); ++i) {
        if (on_robot(hits[i])) {
          misses.push_back(hits[i]);
          if (mirrored) odom_misses->push_back((*odom_hits)[i]);
          ++moved;
        } else {
          if (mirrored) (*odom_hits)[keep] = (*odom_hits)[i];
          hits[keep++] = hits[i];
        }
      }
      hits.resize(keep);
      if (mirrored) odom_hits->resize(keep);
    }
  }
  sightings_[self] = Sighting{position, now_ns};
  return moved;
}

}  // namespace slam::mapper

// RobotFootprints: hits on other robots become misses.
#include "mapper/robot_footprints.hpp"

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

size_t RobotFootprints::apply(std::string_view robot_id, double x, double y, int64_t now_ns,
                              std::vector<Point2d>* hits, std::vector<Point2d>* misses) {
  size_t self = poses_.size();
  if (auto it = slots_.find(robot_id); it != slots_.end()) {
    self = it->second;
  } else {
    slots_.emplace(std::string(robot_id), self);
    poses_.push_back({});
  }
  size_t moved = 0;
  if (radius2_ > 0.0 && !hits->empty()) {
    // Only robots within reach of this observation's farthest hit can be in it.
    double reach2 = 0.0;
    for (const Point2d& p : *hits) reach2 = std::max(reach2, (p.x - x) * (p.x - x) + (p.y - y) * (p.y - y));
    const double reach = std::sqrt(reach2) + std::sqrt(radius2_);
    near_.clear();
    for (size_t i = 0; i < poses_.size(); ++i) {
      const Pose& o = poses_[i];
      if (i == self || now_ns - o.seen_ns > max_age_ns_) continue;
      if ((o.x - x) * (o.x - x) + (o.y - y) * (o.y - y) <= reach * reach) near_.push_back(o);
    }
    if (!near_.empty()) {
      const auto on_robot = [&](const Point2d& p) {
        return std::any_of(near_.begin(), near_.end(), [&](const Pose& o) {
          return (p.x - o.x) * (p.x - o.x) + (p.y - o.y) * (p.y - o.y) <= radius2_;
        });
      };
      // Stable: the remaining hits keep their order; moved ones go to the misses.
      auto keep = hits->begin();
      for (auto it = hits->begin(); it != hits->end(); ++it) {
        if (on_robot(*it)) {
          misses->push_back(*it);
          ++moved;
        } else {
          *keep++ = *it;
        }
      }
      hits->erase(keep, hits->end());
    }
  }
  poses_[self] = Pose{x, y, now_ns};
  return moved;
}

}  // namespace slam::mapper

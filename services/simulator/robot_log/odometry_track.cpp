// Odometry interpolation (odometry_track.hpp).
#include "simulator/robot_log/odometry_track.hpp"

#include <algorithm>

namespace slam::robot_log {

void OdometryTrack::add(double stamp_s, const Pose& pose) {
  if (!samples_.empty() && stamp_s < samples_.back().stamp_s) sorted_ = false;
  samples_.push_back({stamp_s, pose});
}

std::optional<Pose> OdometryTrack::at(double stamp_s) {
  if (samples_.empty()) return std::nullopt;
  if (!sorted_) {
    std::stable_sort(samples_.begin(), samples_.end(),
                     [](const Sample& a, const Sample& b) { return a.stamp_s < b.stamp_s; });
    sorted_ = true;
  }
  const auto after = std::lower_bound(samples_.begin(), samples_.end(), stamp_s,
                                      [](const Sample& s, double t) { return s.stamp_s < t; });
  if (after != samples_.end() && after->stamp_s == stamp_s) return after->pose;
  if (after == samples_.begin()) {
    if (after->stamp_s - stamp_s > max_gap_s_) return std::nullopt;
    return after->pose;
  }
  const auto before = std::prev(after);
  if (after == samples_.end()) {
    if (stamp_s - before->stamp_s > max_gap_s_) return std::nullopt;
    return before->pose;
  }
  const double span = after->stamp_s - before->stamp_s;
  if (span > max_gap_s_) return std::nullopt;
  if (span <= 0) return after->pose;
  const double f = (stamp_s - before->stamp_s) / span;
  const Pose& a = before->pose;
  const Pose& b = after->pose;
  return Pose{a.x + f * (b.x - a.x), a.y + f * (b.y - a.y),
              wrap_angle(a.theta + f * wrap_angle(b.theta - a.theta))};
}

}  // namespace slam::robot_log

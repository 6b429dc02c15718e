#pragma once
// A robot's odometry poses over time, to ask where it was at a scan's stamp: linear between the two
// samples around the stamp (heading the short way round), the nearest sample just outside the
// track, nothing across a gap wider than `max_gap_s` (the robot may have moved anywhere).
#include <optional>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::robot_log {

class OdometryTrack {
 public:
  explicit OdometryTrack(double max_gap_s = 0.5) : max_gap_s_(max_gap_s) {}
  // Samples in any order; they are sorted on the first query after an add.
  void add(double stamp_s, const Pose& pose);
  std::optional<Pose> at(double stamp_s);
  size_t size() const { return samples_.size(); }

 private:
  struct Sample {
    double stamp_s;
    Pose pose;
  };
  double max_gap_s_;
  std::vector<Sample> samples_;
  bool sorted_ = true;
};

}  // namespace slam::robot_log

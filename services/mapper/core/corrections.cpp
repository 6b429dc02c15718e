// Keyframe corrections and the odometry -> map transform of an observation (see corrections.hpp).
#include "mapper/core/corrections.hpp"

#include <cmath>

namespace slam::mapper {
namespace {

void transform_points(const Pose& pose, std::span<const Vec2> in, std::vector<Vec2>& out) {
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  out.resize(in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    const Vec2 p = in[i];
    out[i] = {pose.x + c * p.x - s * p.y, pose.y + s * p.x + c * p.y};
  }
}

}  // namespace

void KeyframeCorrections::set(KeyframeId id, const Pose& map_from_odom) {
  if (id != 0) poses_[id] = map_from_odom;
}

const Pose& KeyframeCorrections::lookup(KeyframeId id) const {
  static const Pose kIdentity{};
  if (id == 0 || poses_.empty()) return kIdentity;
  const auto it = poses_.find(id);
  return it == poses_.end() ? kIdentity : it->second;
}

ObservationView to_map_frame(const Pose& map_from_odom, const ObservationView& odom, std::vector<Vec2>& hits,
                             std::vector<Vec2>& misses) {
  transform_points(map_from_odom, odom.hits, hits);
  transform_points(map_from_odom, odom.misses, misses);
  const Pose sensor = map_from_odom.compose(Pose{odom.x, odom.y, odom.theta});
  return ObservationView{sensor.x,         sensor.y, odom.has_heading ? sensor.theta : 0.0,
                         odom.has_heading, hits,     misses};
}

}  // namespace slam::mapper

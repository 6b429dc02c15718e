// CorrectionTable and the two frame conversions.
#include "gateway/core/frame_correction.hpp"

#include <cmath>

namespace slam::gateway {

Result<bool> CorrectionTable::update(std::string_view robot_id, const Correction& correction) {
  const Pose& t = correction.map_from_odom;
  if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.theta))
    return Error{"correction is not finite"};
  if (auto it = corrections_.find(robot_id); it != corrections_.end()) {
    if (it->second == correction) return false;
    it->second = correction;
    return true;
  }
  if (corrections_.size() >= max_robots_)
    return Error{"corrections of " + std::to_string(max_robots_) + " robots known already (max-robots)"};
  corrections_.emplace(std::string(robot_id), correction);
  return true;
}

Correction CorrectionTable::of(std::string_view robot_id) const {
  auto it = corrections_.find(robot_id);
  return it == corrections_.end() ? Correction{} : it->second;
}

Pose to_map_frame(const Pose& map_from_odom, const Pose& odom_pose, bool has_heading) {
  if (has_heading) return map_from_odom.compose(odom_pose);
  const Vec2 p = map_from_odom.transform(odom_pose.position());
  return {p.x, p.y, odom_pose.theta};
}

void to_odometry_frame(const Pose& map_from_odom, std::span<protocol::Point> points) {
  const Pose odom_from_map = map_from_odom.inverse();
  for (protocol::Point& p : points) {
    const Vec2 odom = odom_from_map.transform({p.x, p.y});
    p = {odom.x, odom.y};
  }
}

}  // namespace slam::gateway

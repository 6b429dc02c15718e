#include "pose_correction/keyframe_builder.hpp"

#include <cmath>
#include <utility>

namespace slam::correction {

KeyframeBuilder::Step KeyframeBuilder::add(uint64_t id, uint32_t robot, int64_t stamp_ns,
                                           const Pose& odom_pose, bool has_heading,
                                           std::span<const Vec2> hits,
                                           std::optional<int64_t> robot_stamp_ns) {
  const int64_t measured_ns = robot_stamp_ns.value_or(stamp_ns);
  const Pose pose{odom_pose.x, odom_pose.y, has_heading ? odom_pose.theta : 0.0};
  if (has_last_ && !jumped_) {
    // By distance only: receive stamps jitter (and a simulator may run faster than real time).
    if (distance(pose.position(), last_pose_.position()) > options_.jump_m) {
      jumped_ = true;
      return Step::Jump;
    }
  }
  if (jumped_) {
    jumped_ = false;
    ++segment_;
  } else if (open_ && keyframe_.scans && static_cast<int>(hits.size()) >= options_.scan_points &&
             (distance(pose.position(), keyframe_.odom.position()) >= options_.scan_travel_m ||
              std::abs(wrap_angle(pose.theta - keyframe_.odom.theta)) >= options_.scan_turn_rad)) {
    return Step::StartsNext;
  }
  has_last_ = true;
  last_pose_ = pose;

  if (!open_) {
    keyframe_.id = id;
    keyframe_.robot = robot;
    keyframe_.segment = segment_;
    keyframe_.odom = pose;
    keyframe_.has_heading = has_heading;
    keyframe_.messages = 0;
    keyframe_.first_stamp_ns = stamp_ns;
    keyframe_.first_robot_stamp_ns = measured_ns;
    keyframe_.travel_m = keyframe_.turn_rad = 0.0;
    keyframe_.scans = true;
    keyframe_.points.clear();
    open_ = true;
  }
  const Pose to_keyframe = keyframe_.odom.inverse();
  for (const Vec2& p : hits) keyframe_.points.push_back(to_keyframe.transform(p));
  ++keyframe_.messages;
  keyframe_.scans = keyframe_.scans && static_cast<int>(hits.size()) >= options_.scan_points;
  keyframe_.last_stamp_ns = stamp_ns;

  const double travel = distance(pose.position(), keyframe_.odom.position());
  const double turn = std::abs(wrap_angle(pose.theta - keyframe_.odom.theta));
  keyframe_.travel_m = std::max(keyframe_.travel_m, travel);
  keyframe_.turn_rad = std::max(keyframe_.turn_rad, turn);
  // A robot clock set back by more than a span leaves the keyframe's span unknown: it closes too.
  const int64_t span_ns = measured_ns - keyframe_.first_robot_stamp_ns;
  const bool complete = travel >= options_.travel_m || turn >= options_.turn_rad ||
                        keyframe_.messages >= options_.max_messages || span_ns >= options_.max_span_ns ||
                        span_ns <= -options_.max_span_ns;
  return complete ? Step::AddedAndClosed : Step::Added;
}

void KeyframeBuilder::start_segment() {
  if (has_last_) jumped_ = true;
}

bool KeyframeBuilder::stale(int64_t now_ns) const {
  return open_ && now_ns - keyframe_.last_stamp_ns >= options_.max_span_ns;
}

Keyframe KeyframeBuilder::take() {
  open_ = false;
  Keyframe out = std::move(keyframe_);
  keyframe_ = Keyframe{};
  return out;
}

}  // namespace slam::correction

#pragma once
// Groups each robot's consecutive observations into keyframes ("multiscans"). One sparse message
// (a v1 robot sends 1-16 points) cannot be matched; the points of a short stretch of travel,
// expressed in the frame of the keyframe's first pose, can. Odometry is trusted over that short
// stretch (its drift over half a metre is a few millimetres).
//
// A keyframe closes after a travel, a turn, a number of messages, or a time span, or sooner once it
// holds enough points to be matched alone (a laser scanner's scan) and the robot moved; an odometry
// step no robot can drive (a reset, a teleport) closes it and starts a new trajectory segment, so
// the jump never becomes a motion in the pose graph.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::correction {

struct KeyframeOptions {
  double travel_m = 0.4;                // close after this much travel...
  double turn_rad = 0.4;                // ...or this much turning (robots that report a heading)...
  int max_messages = 30;                // ...or this many messages...
  int64_t max_span_ns = 4'000'000'000;  // ...or when its messages span this long (either way)
  double jump_m = 1.0;                  // an odometry step longer than this between two messages is a jump
  // A message with at least scan_points points is a laser scanner's scan, matchable alone. A keyframe
  // of scans holds the scans taken within scan_travel_m and scan_turn_rad of its first; the first
  // scan beyond opens the next keyframe (a motion filter: a robot standing still keeps adding scans
  // to one keyframe until one of the limits above). Within a keyframe odometry carries each scan, so
  // it spans centimetres and a few degrees: the half metre a sparse robot's keyframe needs, or even
  // one scan's step of a turn, is where a real robot's odometry goes degrees off.
  int scan_points = 60;
  double scan_travel_m = 0.1;
  double scan_turn_rad = 0.0125;
};

struct Keyframe {
  uint64_t id = 0;
  uint32_t robot = 0;    // the corrector's robot index
  uint32_t segment = 0;  // trajectory segment of the robot
  Pose odom;             // origin in the robot's odometry frame (heading 0 without one)
  bool has_heading = false;
  int messages = 0;
  int64_t first_stamp_ns = 0;  // arrival clock (the corrector's)
  int64_t last_stamp_ns = 0;
  // The robot's own clock when its messages carry one (else the arrival clock): the span it covers.
  int64_t first_robot_stamp_ns = 0;
  // The farthest the robot got from the origin while the keyframe was open (a robot standing
  // still: about zero of both).
  double travel_m = 0.0;
  double turn_rad = 0.0;
  bool scans = true;         // every message was a laser scan (KeyframeOptions::scan_points)
  std::vector<Vec2> points;  // obstacle points in the keyframe's frame
};

// One robot's open keyframe. Plain data; the corrector owns one per robot.
class KeyframeBuilder {
 public:
  enum class Step : uint8_t {
    Added,           // the observation joined the open keyframe
    AddedAndClosed,  // ...and completed it: take() it
    StartsNext,      // the observation belongs to the next keyframe: take() the open one, then call
                     // add() again
    Jump             // the odometry jumped: the open keyframe (if any) must be taken first, then
                     // the observation starts a new segment (call add() again)
  };

  explicit KeyframeBuilder(const KeyframeOptions& options) : options_(options) {}

  // `id` is used when the observation opens a new keyframe. `stamp_ns` is the arrival clock (what
  // stale() is asked against); `robot_stamp_ns`, when the robot sent one, measures the keyframe's
  // span: messages that queued in a broker or a log played fast arrive bunched, not as measured.
  Step add(uint64_t id, uint32_t robot, int64_t stamp_ns, const Pose& odom_pose, bool has_heading,
           std::span<const Vec2> hits, std::optional<int64_t> robot_stamp_ns = std::nullopt);
  // Starts a new segment: the next observation opens a keyframe whatever its distance to the last.
  void start_segment();

  bool open() const { return open_; }
  // Whether the open keyframe's last message is older than max_span_ns at `now_ns` (a silent robot).
  bool stale(int64_t now_ns) const;
  uint64_t open_id() const { return keyframe_.id; }
  // Messages in the open keyframe (0 when none is open).
  int open_messages() const { return open_ ? keyframe_.messages : 0; }
  uint32_t segment() const { return segment_; }
  const Pose& last_odom() const { return last_pose_; }
  bool has_last() const { return has_last_; }

  // Hands over the open keyframe (its buffers are moved out) and closes it.
  Keyframe take();

 private:
  KeyframeOptions options_;
  Keyframe keyframe_;
  bool open_ = false;
  uint32_t segment_ = 0;
  bool has_last_ = false;
  bool jumped_ = false;  // the last add() reported a jump; the next add() opens a new segment
  Pose last_pose_;
};

}  // namespace slam::correction

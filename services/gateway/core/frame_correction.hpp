#pragma once
// The frames contract at the gateway: each robot speaks in its own odometry frame, the mapper
// publishes per robot map_from_odom (PoseCorrection), and the gateway applies it both ways —
// reported poses into the map frame, waypoints and paths into the robot's odometry frame. Plain
// and single-threaded (the gateway's loop owns the table), so the arithmetic is unit-tested alone.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "protocol/codec_types.hpp"

namespace slam::gateway {

// One robot's correction as the gateway uses it. The default is the identity, version 0: what a
// robot the mapper has not corrected yet gets (its odometry frame taken as the map frame).
struct Correction {
  Pose map_from_odom;
  std::uint64_t version = 0;
  bool operator==(const Correction&) const = default;
};

class CorrectionTable {
 public:
  // `max_robots` bounds the memory a stream of made-up robot ids could take.
  explicit CorrectionTable(std::size_t max_robots = 10'000) : max_robots_(max_robots) {}

  // Stores `robot_id`'s correction: true when it differs from the one stored (the robot's state must
  // be republished), false when it is the same. An error, with nothing stored, for a non-finite
  // transform or a new robot once max_robots are known.
  Result<bool> update(std::string_view robot_id, const Correction& correction);
  // The robot's correction; the identity (version 0) for a robot without one.
  Correction of(std::string_view robot_id) const;
  std::size_t size() const { return corrections_.size(); }

 private:
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  std::size_t max_robots_;
  std::unordered_map<std::string, Correction, Hash, std::equal_to<>> corrections_;
};

// A pose the robot reported in its odometry frame, in the map frame. Without a heading (v1) only
// the position is transformed; theta is kept as reported (it carries no meaning).
Pose to_map_frame(const Pose& map_from_odom, const Pose& odom_pose, bool has_heading);

// Map-frame points (a waypoint, a path) into the robot's odometry frame, in place: what every
// command sent to a robot goes through before encoding, whatever the protocol.
void to_odometry_frame(const Pose& map_from_odom, std::span<protocol::Point> points);

}  // namespace slam::gateway

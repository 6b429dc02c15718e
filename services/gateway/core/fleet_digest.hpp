#pragma once
// The gateway's fleet digests: every robot this gateway knows (map-frame pose, presence, last
// message) and each robot's latest obstacle points, gathered into one sample per period for the
// bridge, which would otherwise take every RobotState and RobotObservation (one datagram each).
// Plain and single-threaded: the gateway's loop alone calls it. Buffers are reused: once every robot has
// been seen, building a digest allocates nothing.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/core/geometry.hpp"
#include "gateway/core/frame_correction.hpp"
#include "gateway/core/robot_registry.hpp"
#include "protocol/codec_types.hpp"

namespace slam::gateway {

struct DigestRobotEntry {
  std::string id;
  Pose pose;  // odometry frame after collect, map frame after place
  bool has_pose = false;
  bool has_heading = false;
  bool online = false;
  std::int64_t last_seen_ns = 0;
};

struct DigestPointsEntry {
  std::string id;
  std::int64_t stamp_ns = 0;  // receive time of the newest observation among the points
  std::vector<Vec2> points;   // odometry frame after take_points, map frame after place
};

class FleetDigestBuilder {
 public:
  // Keeps each robot's latest `points_per_robot` hits between two take_points.
  explicit FleetDigestBuilder(std::size_t points_per_robot) : points_per_robot_(points_per_robot) {}

  // An accepted observation's hits (odometry frame), received at `stamp_ns`.
  void add_hits(std::string_view id, std::span<const protocol::Point> hits, std::int64_t stamp_ns);
  // The robot was forgotten: its pending points go.
  void forget(std::string_view id);

  // Copies every robot of `registry` (pose still in the odometry frame) into robots().
  void collect(const RobotRegistry& registry);
  // Moves the points added since the last call into points() (robots without new points left out).
  void take_points();
  // Puts what collect copied into the map frame through each robot's correction (once per collect).
  void place_robots(const CorrectionTable& corrections);
  // The same for what take_points took (once per take_points).
  void place_points(const CorrectionTable& corrections);

  std::span<const DigestRobotEntry> robots() const { return {robots_.data(), robot_count_}; }
  std::span<const DigestPointsEntry> points() const { return {taken_.data(), taken_count_}; }

 private:
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  // The latest hits of one robot since the last take: a ring of points_per_robot_.
  struct Pending {
    std::vector<Vec2> ring;
    std::size_t next = 0;
    std::int64_t stamp_ns = 0;
  };

  std::size_t points_per_robot_;
  std::unordered_map<std::string, Pending, Hash, std::equal_to<>> pending_;
  std::vector<DigestRobotEntry> robots_;
  std::size_t robot_count_ = 0;
  std::vector<DigestPointsEntry> taken_;
  std::size_t taken_count_ = 0;
};

}  // namespace slam::gateway
